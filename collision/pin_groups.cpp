#include "collision/pin_groups.hpp"

#include <cstddef>
#include <numeric>

namespace weft {

using std::size_t;

PinGroups pin_groups(const std::vector<std::array<int, 3>>& triangles, const std::vector<char>& pinned) {
  const size_t n = pinned.size();
  std::vector<int> root(n);
  std::iota(root.begin(), root.end(), 0);
  auto find = [&](int a) {
    while (root[size_t(a)] != a) a = root[size_t(a)] = root[size_t(root[size_t(a)])];
    return a;
  };
  std::vector<char> joined(n, 0);
  for (const std::array<int, 3>& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[size_t(k)], b = t[size_t((k + 1) % 3)];
      if (!pinned[size_t(a)] || !pinned[size_t(b)]) continue;
      joined[size_t(a)] = joined[size_t(b)] = 1;
      const int ra = find(a), rb = find(b);
      if (ra != rb) root[size_t(ra < rb ? rb : ra)] = ra < rb ? ra : rb;  // the lower point roots the group
    }
  PinGroups g;
  g.group.assign(n, -1);
  std::vector<int> id(n, -1);
  for (size_t i = 0; i < n; ++i) {
    if (!joined[i]) continue;
    const size_t r = size_t(find(int(i)));
    if (id[r] < 0) id[r] = g.count++;
    g.group[i] = id[r];
  }
  return g;
}

}  // namespace weft
