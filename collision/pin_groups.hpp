// Pins that hold back together (docs/collisions.md, "Pin groups"): the pins joined by the cloth's edges form
// a group, the handle an artist pins (a twisted sheet's edge, a waistband). Where its bounds hold a
// pin short of its target, every pin of the group takes the same fraction of its move, so a jammed handle
// stalls as a whole, keeping its shape, instead of each pin trailing by its own amount and the cloth between
// them torn apart.
#pragma once
#include <array>
#include <vector>

namespace weft {

struct PinGroups {
  std::vector<int> group;  // per point: its group, or -1 (free, or a pin with no pinned neighbour)
  int count = 0;
};

// `pinned[i]`: point i is a pin (the collision stage passes those that follow an animation). Groups are
// numbered by their lowest point.
PinGroups pin_groups(const std::vector<std::array<int, 3>>& triangles, const std::vector<char>& pinned);

}  // namespace weft
