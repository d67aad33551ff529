// Per-point (vertex-block) Gauss-Seidel beside row-by-row XPBD Gauss-Seidel, on the same rows (the hanging
// sheet's distance and bend rows) and the same start: what a sweep costs and how far a number of sweeps
// gets. A row sweep projects one row per thread, colour by colour (rows sharing no moving point); a
// vertex-block sweep moves one point per thread, colour by colour (points sharing no row), by a
// Gauss-Newton step on its inertia and all its rows' energies C^2 / (2 alpha~) (Vertex Block Descent, Chen
// et al. 2024) damped as Levenberg-Marquardt, each row evaluated at the current positions. Both converge to
// the same positions: the minimum of inertia plus row energies. The chain of dependent steps of a sweep is
// its colour count.
//
// Start: the sheet one substep in, every moving point displaced by up to a tenth of the grid's edge along
// each axis (a fixed pseudo-random pattern), the inertial target y where it stands before the displacement. Counters: the
// colours, and after 20 and 100 sweeps from that start the distance rows' max and rms |length / rest - 1|.
#pragma once
#include "bench/micro/bench_common.hpp"
#include "bench/micro/cloth_grid.hpp"
#include "constraints/build_rows.hpp"
#include "solver/solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace {

using Exec = WEFT_BENCH_EXECSPACE;
using Mem = Exec::memory_space;
using weft::real;
using weft::Vec3;

struct VbRow {
  int kind;  // kRowDistance or kRowBend
  int idx[4];
  real rest, compliance, compress;
};

KOKKOS_INLINE_FUNCTION real vb_eval(const VbRow& r, const Kokkos::View<Vec3*, Mem>& x, Vec3 (&g)[4]) {
  if (r.kind == weft::kRowDistance) {
    Vec3 g2[2];
    const real c = weft::distance_eval(x(r.idx[0]), x(r.idx[1]), r.rest, g2);
    g[0] = g2[0];
    g[1] = g2[1];
    g[2] = g[3] = Vec3{0, 0, 0};
    return c;
  }
  return weft::bend_eval(x(r.idx[0]), x(r.idx[1]), x(r.idx[2]), x(r.idx[3]), r.rest, g);
}

KOKKOS_INLINE_FUNCTION int vb_points(const VbRow& r) { return r.kind == weft::kRowDistance ? 2 : 4; }

// One row of a colour, XPBD (no damping).
struct RowStep {
  Kokkos::View<const VbRow*, Mem> rows;
  Kokkos::View<const int*, Mem> order;
  Kokkos::View<Vec3*, Mem> x;
  Kokkos::View<const real*, Mem> w;
  Kokkos::View<real*, Mem> lambda;
  real h2;
  long first;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const int r = order(first + i);
    const VbRow row = rows(r);
    Vec3 g[4];
    const real c = vb_eval(row, x, g);
    const int n = vb_points(row);
    real wg = 0;
    for (int k = 0; k < n; ++k) wg += w(row.idx[k]) * weft::dot(g[k], g[k]);
    const real alpha = (c < 0 ? row.compress : row.compliance) / h2;
    const real denom = wg + alpha;
    if (!(wg > 0) || !(denom > 0)) return;
    const real dl = (-c - alpha * lambda(r)) / denom;
    lambda(r) += dl;
    for (int k = 0; k < n; ++k) x(row.idx[k]) = x(row.idx[k]) + (w(row.idx[k]) * dl) * g[k];
  }
};

// One point of a colour: x += -H^-1 f, H = m / h^2 I + sum g g^T / alpha~, f = m / h^2 (x - y) + sum C g / alpha~.
struct PointStep {
  Kokkos::View<const VbRow*, Mem> rows;
  Kokkos::View<const int*, Mem> order, begin, entry_row, entry_slot;
  Kokkos::View<Vec3*, Mem> x;
  Kokkos::View<const Vec3*, Mem> y;
  Kokkos::View<const real*, Mem> w;
  real h2;
  long first;
  static constexpr real kDamping = 0.01;  // times the largest diagonal term (0.005 to 0.3 converged here, 0 did not)
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const int p = order(first + i);
    const real m = 1 / (w(p) * h2);
    const Vec3 xp = x(p), d = xp - y(p);
    real H[6] = {m, 0, 0, m, 0, m};  // xx xy xz yy yz zz
    Vec3 f = m * d;
    for (int e = begin(p); e < begin(p + 1); ++e) {
      const VbRow row = rows(entry_row(e));
      Vec3 g[4];
      const real c = vb_eval(row, x, g);
      const real alpha = (c < 0 ? row.compress : row.compliance) / h2;
      if (!(alpha > 0) || !(alpha < 1e300)) continue;
      const real k = 1 / alpha;
      const Vec3 gk = g[entry_slot(e)];
      H[0] += k * gk.x * gk.x;
      H[1] += k * gk.x * gk.y;
      H[2] += k * gk.x * gk.z;
      H[3] += k * gk.y * gk.y;
      H[4] += k * gk.y * gk.z;
      H[5] += k * gk.z * gk.z;
      f = f + (k * c) * gk;
    }
    // Levenberg-Marquardt damping: a flat sheet's points have almost no stiffness across it (the rows pull
    // in its plane, the inertia is tiny beside them), and undamped steps across it grew without bound.
    // The damping changes the step, not the minimum it converges to.
    const real mu = kDamping * weft::max_(H[0], weft::max_(H[3], H[5]));
    H[0] += mu;
    H[3] += mu;
    H[5] += mu;
    // Symmetric 3x3 solve by the adjugate.
    const real a00 = H[3] * H[5] - H[4] * H[4], a01 = H[2] * H[4] - H[1] * H[5], a02 = H[1] * H[4] - H[2] * H[3];
    const real a11 = H[0] * H[5] - H[2] * H[2], a12 = H[1] * H[2] - H[0] * H[4], a22 = H[0] * H[3] - H[1] * H[1];
    const real det = H[0] * a00 + H[1] * a01 + H[2] * a02;
    if (!(det > 0)) return;
    const Vec3 dx{-(a00 * f.x + a01 * f.y + a02 * f.z) / det, -(a01 * f.x + a11 * f.y + a12 * f.z) / det,
                  -(a02 * f.x + a12 * f.y + a22 * f.z) / det};
    x(p) = xp + dx;
  }
};

// Greedy colouring in index order of items that each touch a few of `points` points: an item takes the
// smallest colour none of its points has yet. Returns per item its colour.
std::vector<int> greedy_colours(const std::vector<std::vector<int>>& items, long points) {
  std::vector<uint64_t> used(points, 0);
  std::vector<int> colour(items.size());
  for (size_t i = 0; i < items.size(); ++i) {
    uint64_t taken = 0;
    for (int p : items[i]) taken |= used[p];
    int c = 0;
    while (c < 63 && ((taken >> c) & 1)) ++c;
    colour[i] = c;
    for (int p : items[i]) used[p] |= uint64_t(1) << c;
  }
  return colour;
}

// Items of each colour in index order: `order` lists them colour by colour, `offsets` where each starts.
void by_colour(const std::vector<int>& colour, std::vector<int>& order, std::vector<long>& offsets) {
  const int n = colour.empty() ? 0 : *std::max_element(colour.begin(), colour.end()) + 1;
  offsets.assign(n + 1, 0);
  for (int c : colour) ++offsets[c + 1];
  for (int c = 0; c < n; ++c) offsets[c + 1] += offsets[c];
  order.assign(colour.size(), 0);
  std::vector<long> at(offsets.begin(), offsets.end() - 1);
  for (size_t i = 0; i < colour.size(); ++i) order[at[colour[i]]++] = int(i);
}

struct VertexBlockFixture {
  Kokkos::View<VbRow*, Mem> rows;
  Kokkos::View<int*, Mem> row_order, point_order, begin, entry_row, entry_slot;
  std::vector<long> row_offsets, point_offsets;
  Kokkos::View<Vec3*, Mem> x, y, start;
  Kokkos::View<real*, Mem> w, lambda;
  real h2 = 0;
  long distance_rows = 0;
  double strain[2][2][2] = {};  // [method: rows, points][after 20, 100][max, rms]

  explicit VertexBlockFixture(long triangles) {
    const weft::Scene scene = weft::bench::hanging_sheet(triangles);
    const real h = 1 / (scene.settings.fps * scene.settings.substeps);
    h2 = h * h;
    weft::Solver<Exec> solver(scene);
    solver.substep(0);
    Exec().fence();
    const auto& st = solver.state();
    const long np = long(st.x.extent(0));
    auto hw = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.w);
    auto hx = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.x);

    std::vector<VbRow> host;
    std::vector<std::vector<int>> row_points;
    for (const weft::Row& r : weft::build_rows(scene, {})) {
      if (r.kind != weft::kRowDistance && r.kind != weft::kRowBend) continue;
      VbRow v{r.kind, {-1, -1, -1, -1}, r.rest, r.m.compliance, r.m.compress_compliance};
      std::vector<int> moving;
      for (int k = 0; k < (r.kind == weft::kRowDistance ? 2 : 4); ++k) {
        v.idx[k] = r.idx[k];
        if (hw(r.idx[k]) > 0) moving.push_back(r.idx[k]);
      }
      if (moving.empty()) continue;
      host.push_back(v);
      row_points.push_back(moving);
      distance_rows += r.kind == weft::kRowDistance;
    }
    // Rows by colour (rows sharing no moving point).
    std::vector<int> rorder;
    by_colour(greedy_colours(row_points, np), rorder, row_offsets);
    // Per moving point its rows (CSR, in row order) and its slot in each; points coloured so that two
    // points of one colour share no row.
    std::vector<std::vector<std::pair<int, int>>> of(np);
    for (size_t r = 0; r < host.size(); ++r)
      for (int k = 0; k < vb_points(host[r]); ++k)
        if (hw(host[r].idx[k]) > 0) of[host[r].idx[k]].push_back({int(r), k});
    std::vector<std::vector<int>> neighbours;  // per moving point, the points of its rows
    std::vector<int> moving_points;
    for (long p = 0; p < np; ++p) {
      if (!(hw(p) > 0)) continue;
      moving_points.push_back(int(p));
      std::vector<int> nb;
      for (auto [r, k] : of[p])
        for (int j = 0; j < vb_points(host[r]); ++j) nb.push_back(host[r].idx[j]);
      std::sort(nb.begin(), nb.end());
      nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
      neighbours.push_back(nb);
    }
    // A point's colour must differ from every neighbour's: colour points in order, each taking the
    // smallest colour no coloured neighbour has.
    std::vector<int> pcolour(np, -1), mcolour(moving_points.size());
    for (size_t i = 0; i < moving_points.size(); ++i) {
      uint64_t taken = 0;
      for (int q : neighbours[i])
        if (pcolour[q] >= 0) taken |= uint64_t(1) << pcolour[q];
      int c = 0;
      while (c < 63 && ((taken >> c) & 1)) ++c;
      pcolour[moving_points[i]] = mcolour[i] = c;
    }
    std::vector<int> porder_local, porder;
    by_colour(mcolour, porder_local, point_offsets);
    for (int i : porder_local) porder.push_back(moving_points[i]);
    std::vector<int> hbegin(np + 1, 0), hrow, hslot;
    for (long p = 0; p < np; ++p) {
      for (auto [r, k] : of[p]) {
        hrow.push_back(r);
        hslot.push_back(k);
      }
      hbegin[p + 1] = int(hrow.size());
    }
    rows = weft::bench::upload<Mem>(host, "vb::rows");
    row_order = weft::bench::upload<Mem>(rorder, "vb::row_order");
    point_order = weft::bench::upload<Mem>(porder, "vb::point_order");
    begin = weft::bench::upload<Mem>(hbegin, "vb::begin");
    entry_row = weft::bench::upload<Mem>(hrow, "vb::entry_row");
    entry_slot = weft::bench::upload<Mem>(hslot, "vb::entry_slot");
    w = Kokkos::View<real*, Mem>("vb::w", np);
    Kokkos::deep_copy(w, st.w);
    lambda = Kokkos::View<real*, Mem>("vb::lambda", host.size());
    // The start: y where the sheet stands, x displaced from it by a fixed pattern.
    auto hs = Kokkos::create_mirror_view(hx);
    const real edge = 1.0 / weft::bench::grid_res(triangles);
    for (long p = 0; p < np; ++p) {
      hs(p) = hx(p);
      if (hw(p) > 0)
        for (int a = 0; a < 3; ++a) hs(p)[a] += 0.1 * edge * (2 * weft::bench::unit_random(7, uint64_t(3 * p + a)) - 1);
    }
    y = Kokkos::View<Vec3*, Mem>("vb::y", np);
    start = Kokkos::View<Vec3*, Mem>("vb::start", np);
    x = Kokkos::View<Vec3*, Mem>("vb::x", np);
    Kokkos::deep_copy(y, st.x);
    Kokkos::deep_copy(start, hs);
    for (int method = 0; method < 2; ++method) {
      restart();
      int done = 0;
      for (int at = 0; at < 2; ++at) {
        const int upto = at == 0 ? 20 : 100;
        for (; done < upto; ++done) method == 0 ? row_sweep() : point_sweep();
        measure(strain[method][at]);
      }
    }
    restart();
  }

  void restart() {
    Kokkos::deep_copy(x, start);
    Kokkos::deep_copy(lambda, 0.0);
  }
  void row_sweep() {
    const Exec exec;
    for (size_t c = 0; c + 1 < row_offsets.size(); ++c)
      Kokkos::parallel_for("vb::row_colour", Kokkos::RangePolicy<Exec>(exec, 0, row_offsets[c + 1] - row_offsets[c]),
                           RowStep{rows, row_order, x, w, lambda, h2, row_offsets[c]});
  }
  void point_sweep() {
    const Exec exec;
    for (size_t c = 0; c + 1 < point_offsets.size(); ++c)
      Kokkos::parallel_for("vb::point_colour",
                           Kokkos::RangePolicy<Exec>(exec, 0, point_offsets[c + 1] - point_offsets[c]),
                           PointStep{rows, point_order, begin, entry_row, entry_slot, x, y, w, h2, point_offsets[c]});
  }
  // The distance rows' max and rms |length / rest - 1| (on the host).
  void measure(double (&out)[2]) const {
    Exec().fence();
    auto hx = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x);
    auto hr = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), rows);
    double mx = 0, sum = 0;
    long n = 0;
    for (size_t r = 0; r < hr.extent(0); ++r) {
      if (hr(r).kind != weft::kRowDistance || !(hr(r).rest > 0)) continue;
      const double s = std::abs(weft::norm(hx(hr(r).idx[1]) - hx(hr(r).idx[0])) / hr(r).rest - 1);
      mx = std::max(mx, s);
      sum += s * s;
      ++n;
    }
    out[0] = mx;
    out[1] = n ? std::sqrt(sum / n) : 0;
  }
};

void counters(benchmark::State& state, const VertexBlockFixture& f, int method, long colours) {
  state.counters["colours"] = double(colours);
  state.counters["max_20"] = f.strain[method][0][0];
  state.counters["rms_20"] = f.strain[method][0][1];
  state.counters["max_100"] = f.strain[method][1][0];
  state.counters["rms_100"] = f.strain[method][1][1];
}

void sweep_by_rows(benchmark::State& state) {
  VertexBlockFixture& f = weft::bench::fixture<VertexBlockFixture>(state.range(0));
  f.restart();
  for (auto _ : state) {
    f.row_sweep();
    Exec().fence();
  }
  counters(state, f, 0, long(f.row_offsets.size()) - 1);
}

void sweep_by_points(benchmark::State& state) {
  VertexBlockFixture& f = weft::bench::fixture<VertexBlockFixture>(state.range(0));
  f.restart();
  for (auto _ : state) {
    f.point_sweep();
    Exec().fence();
  }
  counters(state, f, 1, long(f.point_offsets.size()) - 1);
}

void vertex_block_sizes(benchmark::internal::Benchmark* b) {
  weft::bench::sizes(b, "tris", {10000, 100000, 300000});
  b->Unit(benchmark::kMicrosecond);
}
BENCHMARK(sweep_by_rows)->Apply(vertex_block_sizes);
BENCHMARK(sweep_by_points)->Apply(vertex_block_sizes);

}  // namespace
