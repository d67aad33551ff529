// The solver instantiated for Kokkos::Cuda.
#include "backends/simulation_on.hpp"

namespace weft {
std::unique_ptr<Simulation> make_simulation_cuda(const Scene& s) { return std::make_unique<SimulationOn<Kokkos::Cuda>>(s); }
}  // namespace weft
