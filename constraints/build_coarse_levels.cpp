#include "constraints/build_coarse_levels.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <utility>

namespace weft {

namespace {

// A link of a level's graph: its rest length along the cloth and its compliance (its rows in series).
struct Link {
  real rest = std::numeric_limits<real>::infinity();
  real compliance = 0;
};

using Links = std::map<std::pair<int, int>, Link>;  // (lower point, higher point)

// Keeps the shorter of two links between the same points (ties: the lower compliance).
void keep_shorter(Links& links, int a, int b, Link l) {
  if (a == b) return;
  Link& have = links[{std::min(a, b), std::max(a, b)}];
  if (l.rest < have.rest || (l.rest == have.rest && l.compliance < have.compliance)) have = l;
}

}  // namespace

std::vector<CoarseLevel> build_coarse_levels(const Scene& s, const std::vector<real>& w) {
  const int levels = s.settings.coarse_levels;
  const size_t n = s.points.size();
  if (levels <= 0 || n == 0) return {};
  Links links;
  for (const DistanceConstraint& d : s.constraints.distance)
    if (d.a != d.b) keep_shorter(links, d.a, d.b, Link{d.rest, d.m.compliance});
  std::vector<int> on;  // the level's points, ascending
  {
    std::vector<char> has(n, 0);
    for (const auto& [ab, l] : links) has[size_t(ab.first)] = has[size_t(ab.second)] = 1;
    for (size_t i = 0; i < n; ++i)
      if (has[i]) on.push_back(int(i));
  }
  std::vector<CoarseLevel> out;
  std::vector<std::vector<std::pair<int, Link>>> nbr(n);  // per point, its neighbours on the current level
  std::vector<char> coarse(n, 0);
  while (int(out.size()) < levels && on.size() > 1) {
    for (int p : on) nbr[size_t(p)].clear();
    for (const auto& [ab, l] : links) {
      nbr[size_t(ab.first)].push_back({ab.second, l});
      nbr[size_t(ab.second)].push_back({ab.first, l});
    }
    // The coarse points: those that do not move first, then the rest, each by index.
    std::vector<int> order;
    for (int pass = 0; pass < 2; ++pass)
      for (int p : on)
        if ((w[size_t(p)] == 0) == (pass == 0)) order.push_back(p);
    std::vector<int> next;
    for (int p : order) {
      bool free = true;
      for (const auto& [q, l] : nbr[size_t(p)]) free = free && !coarse[size_t(q)];
      if (free) {
        coarse[size_t(p)] = 1;
        next.push_back(p);
      }
    }
    std::sort(next.begin(), next.end());
    if (next.size() == on.size()) break;  // no links left to coarsen
    CoarseLevel lv;
    lv.offset.push_back(0);
    for (int p : on) {
      if (coarse[size_t(p)]) continue;
      real sum = 0;
      const size_t first = lv.parent.size();
      for (const auto& [q, l] : nbr[size_t(p)])
        if (coarse[size_t(q)]) {
          lv.parent.push_back(q);
          lv.weight.push_back(l.rest > 0 ? 1 / l.rest : 1);
          sum += lv.weight.back();
        }
      for (size_t k = first; k < lv.parent.size(); ++k) lv.weight[k] /= sum;
      lv.follower.push_back(p);
      lv.offset.push_back(long(lv.parent.size()));
    }
    // The next level's links: coarse a - follower m - coarse b, and coarse a - m1 - m2 - coarse b.
    Links up;
    const auto chain = [](Link x, Link y) { return Link{x.rest + y.rest, x.compliance + y.compliance}; };
    for (int m : lv.follower)
      for (const auto& [a, la] : nbr[size_t(m)]) {
        if (!coarse[size_t(a)]) continue;
        for (const auto& [b, lb] : nbr[size_t(m)]) {
          if (coarse[size_t(b)]) {
            if (a < b) keep_shorter(up, a, b, chain(la, lb));
            continue;
          }
          for (const auto& [c, lc] : nbr[size_t(b)])
            if (coarse[size_t(c)] && c != a) keep_shorter(up, a, c, chain(chain(la, lb), lc));
        }
      }
    for (const auto& [ab, l] : up) {
      if (w[size_t(ab.first)] == 0 && w[size_t(ab.second)] == 0) continue;
      Row r;
      r.kind = kRowDistance;
      r.n = 2;
      r.idx[0] = ab.first;
      r.idx[1] = ab.second;
      r.rest = l.rest;
      r.m.compliance = l.compliance;
      r.m.compress_compliance = std::numeric_limits<real>::infinity();  // pulls only
      r.m.damping_ratio = 0;
      lv.rows.push_back(r);
    }
    for (int p : next) coarse[size_t(p)] = 0;
    if (lv.rows.empty()) break;  // nothing on the level moves: its followers would not either
    out.push_back(std::move(lv));
    links.swap(up);
    on.swap(next);
  }
  return out;
}

}  // namespace weft
