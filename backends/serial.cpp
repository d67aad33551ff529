// The solver instantiated for Kokkos::Serial.
#include "backends/simulation_on.hpp"

namespace weft {
std::unique_ptr<Simulation> make_simulation_serial(const Scene& s) { return std::make_unique<SimulationOn<Kokkos::Serial>>(s); }
}  // namespace weft
