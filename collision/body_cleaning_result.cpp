#include "collision/body_cleaning_result.hpp"

#include <cstdio>

namespace weft {

std::string cleaning_summary(const BodyCleaning& c, long cloth_pairs) {
  char buf[320], cloth[96] = "";
  if (cloth_pairs > 0) std::snprintf(cloth, sizeof cloth, ", %ld cloth triangle pairs intersecting at the start", cloth_pairs);
  std::snprintf(buf, sizeof buf, "check: %zu frames, %ld points moved (largest %.3g m), %ld violations left%s: %s",
                c.frames.size(), c.points_moved(), c.max_displacement(), c.violations_left(), cloth,
                c.clean() && cloth_pairs == 0 ? "clean" : "NOT clean");
  return buf;
}

}  // namespace weft
