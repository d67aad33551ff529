#include "collision/body_cleaning_result.hpp"

#include <cstdio>

namespace weft {

std::string cleaning_summary(const BodyCleaning& c) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "check: %zu frames, %ld points moved (largest %.3g m), %ld violations left: %s",
                c.frames.size(), c.points_moved(), c.max_displacement(), c.violations_left(),
                c.clean() ? "clean" : "NOT clean");
  return buf;
}

}  // namespace weft
