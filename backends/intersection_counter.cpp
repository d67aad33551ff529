#include "backends/intersection_counter.hpp"

#include "backends/dispatch.hpp"
#include "backends/on_backend.hpp"

namespace weft {

std::unique_ptr<IntersectionCounter> make_intersection_counter(Backend b, const std::string& name,
                                                               const std::vector<std::array<int, 3>>& tris) {
  return with_backend(b, [&](auto on) {
    return OnBackend<typename decltype(on)::exec>::make_intersection_counter(name, tris);
  });
}

}  // namespace weft
