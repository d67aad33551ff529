// The solver and the solvability check instantiated for Kokkos::Serial. They share one translation unit so
// that the templates they both use (LBVH, sort, reductions) are instantiated for this backend only once.
#include "backends/simulation_on.hpp"
#include "collision/body_cleaning.hpp"

namespace weft {
std::unique_ptr<Simulation> make_simulation_serial(const Scene& s) { return std::make_unique<SimulationOn<Kokkos::Serial>>(s); }
BodyCleaning clean_body_serial(const Scene& s, const CleaningSettings& cs) { return clean_body_on<Kokkos::Serial>(s, cs); }
}  // namespace weft
