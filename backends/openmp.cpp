// The solver and the solvability check instantiated for Kokkos::OpenMP. They share one translation unit so
// that the templates they both use (LBVH, sort, reductions) are instantiated for this backend only once.
#include "backends/simulation_on.hpp"
#include "collision/body_cleaning.hpp"

namespace weft {
std::unique_ptr<Simulation> make_simulation_openmp(const Scene& s) { return std::make_unique<SimulationOn<Kokkos::OpenMP>>(s); }
BodyCleaning clean_body_openmp(const Scene& s, const CleaningSettings& cs) { return clean_body_on<Kokkos::OpenMP>(s, cs); }
}  // namespace weft
