#include "backends/simulation.hpp"

#include "backends/dispatch.hpp"
#include "backends/on_backend.hpp"

namespace weft {

std::unique_ptr<Simulation> make_simulation(Backend b, const Scene& scene) {
  return with_backend(b, [&](auto on) { return OnBackend<typename decltype(on)::exec>::make_simulation(scene); });
}

}  // namespace weft
