#include "backends/body_cleaning.hpp"

#include "backends/dispatch.hpp"
#include "backends/on_backend.hpp"
#include "collision/body_cleaning_input.hpp"

namespace weft {

BodyCleaning clean_body(Backend b, const Scene& scene, const CleaningSettings& settings) {
  validate_scene(scene);
  check_collider_orientation(scene);
  return with_backend(b, [&](auto on) { return OnBackend<typename decltype(on)::exec>::clean_body(scene, settings); });
}

}  // namespace weft
