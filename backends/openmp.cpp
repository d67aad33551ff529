// The solver instantiated for Kokkos::OpenMP.
#include "backends/simulation_on.hpp"

namespace weft {
std::unique_ptr<Simulation> make_simulation_openmp(const Scene& s) { return std::make_unique<SimulationOn<Kokkos::OpenMP>>(s); }
}  // namespace weft
