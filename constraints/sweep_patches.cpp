#include "constraints/sweep_patches.hpp"

#include "core/error.hpp"
#include "core/morton.hpp"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>


namespace weft {
namespace {

constexpr long round8(long bytes) { return (bytes + 7) / 8 * 8; }

// The patches for P moving points per patch, or the first patch that does not fit kPatchScratchBytes.
struct Attempt {
  std::optional<SweepPatches> patches;
  int too_big_point = -1;  // the first moving point of a patch that does not fit
};

// Patches grown breadth-first over the rows' links between moving points, each from the first point in
// Morton order that no patch has taken yet, until it holds P points: compact patches, so that each has few
// neighbours and the patches need few colours. Returns each point's patch (-1: it does not move) and the count.
long grow_patches(const std::vector<Row>& rows, const std::vector<int>& by_rank, const std::vector<char>& movable, int P,
                  std::vector<long>& point_patch) {
  const long n = long(movable.size());
  std::vector<long> off(size_t(n) + 1, 0);
  for (const Row& r : rows)
    for (int a = 0; a < r.n; ++a)
      if (movable[r.idx[a]]) off[size_t(r.idx[a]) + 1] += r.n - 1;
  for (long i = 0; i < n; ++i) off[size_t(i) + 1] += off[size_t(i)];
  std::vector<int> links(static_cast<size_t>(off[size_t(n)]));
  {
    std::vector<long> fill(off.begin(), off.end() - 1);
    for (const Row& r : rows)
      for (int a = 0; a < r.n; ++a)
        if (movable[r.idx[a]])
          for (int b = 0; b < r.n; ++b)
            if (b != a) links[size_t(fill[size_t(r.idx[a])]++)] = r.idx[b];
  }
  point_patch.assign(size_t(n), -1);
  std::vector<int> queue;
  long np = 0;
  for (int seed : by_rank) {
    if (point_patch[size_t(seed)] >= 0) continue;
    queue.assign(1, seed);
    point_patch[size_t(seed)] = np;
    long taken = 1;
    for (size_t head = 0; head < queue.size() && taken < P; ++head) {
      const int u = queue[head];
      for (long k = off[size_t(u)]; k < off[size_t(u) + 1] && taken < P; ++k) {
        const int v = links[size_t(k)];
        if (!movable[size_t(v)] || point_patch[size_t(v)] >= 0) continue;
        point_patch[size_t(v)] = np;
        queue.push_back(v);
        ++taken;
      }
    }
    ++np;
  }
  return std::max(1L, np);
}

Attempt build_for(const std::vector<Row>& rows, const std::vector<int>& by_rank, const std::vector<char>& movable, int P) {
  const long n = long(movable.size()), nr = long(rows.size());
  std::vector<long> point_patch;
  const long np = grow_patches(rows, by_rank, movable, P, point_patch);

  // Each row goes to the first patch among its moving points'; a row that moves nothing changes no position
  // and is left out of the sweep.
  std::vector<long> row_off(size_t(np) + 1, 0);
  std::vector<long> row_patch(size_t(nr), -1);
  for (long r = 0; r < nr; ++r) {
    long best = -1;
    for (int k = 0; k < rows[r].n; ++k) {
      const int i = rows[r].idx[k];
      if (movable[i] && (best < 0 || point_patch[size_t(i)] < best)) best = point_patch[size_t(i)];
    }
    if (best < 0) continue;
    row_patch[r] = best;
    ++row_off[size_t(row_patch[r]) + 1];
  }
  for (long p = 0; p < np; ++p) row_off[size_t(p) + 1] += row_off[size_t(p)];
  std::vector<long> patch_rows(static_cast<size_t>(row_off[size_t(np)]));
  {
    std::vector<long> fill(row_off.begin(), row_off.end() - 1);
    for (long r = 0; r < nr; ++r)
      if (row_patch[r] >= 0) patch_rows[size_t(fill[size_t(row_patch[r])]++)] = r;
  }

  // Per patch: its point table, its rows' places in it, and its rows coloured among themselves (greedy in
  // row order over the moving points).
  SweepPatches out;
  out.patch_points = P;
  out.local.assign(size_t(nr), {-1, -1, -1, -1, -1});
  std::vector<std::vector<int>> tables(static_cast<size_t>(np));
  std::vector<int> row_colour(size_t(nr), 0), cells(size_t(np), 0);
  std::vector<std::vector<uint64_t>> used;
  for (long p = 0; p < np; ++p) {
    std::vector<int>& t = tables[size_t(p)];
    for (long k = row_off[size_t(p)]; k < row_off[size_t(p) + 1]; ++k) {
      const Row& row = rows[size_t(patch_rows[size_t(k)])];
      t.insert(t.end(), row.idx, row.idx + row.n);
    }
    std::sort(t.begin(), t.end());
    t.erase(std::unique(t.begin(), t.end()), t.end());
    used.assign(t.size(), {});
    std::array<long, kRowKinds> kind_rows{};
    int ncell = 0;
    for (long k = row_off[size_t(p)]; k < row_off[size_t(p) + 1]; ++k) {
      const long r = patch_rows[size_t(k)];
      const Row& row = rows[size_t(r)];
      ++kind_rows[size_t(row.kind)];
      int at[5];
      for (int j = 0; j < row.n; ++j) {
        at[j] = int(std::lower_bound(t.begin(), t.end(), row.idx[j]) - t.begin());
        out.local[size_t(r)][size_t(j)] = at[j];
      }
      int c = 0;
      for (;; ++c) {
        bool free = true;
        for (int j = 0; j < row.n && free; ++j) {
          if (!movable[row.idx[j]]) continue;
          const auto& u = used[size_t(at[j])];
          const size_t word = size_t(c) / 64;
          free = !(word < u.size() && (u[word] >> (c % 64) & 1ull));
        }
        if (free) break;
      }
      for (int j = 0; j < row.n; ++j) {
        if (!movable[row.idx[j]]) continue;
        auto& u = used[size_t(at[j])];
        const size_t word = size_t(c) / 64;
        if (u.size() <= word) u.resize(word + 1, 0ull);
        u[word] |= 1ull << (c % 64);
      }
      row_colour[size_t(r)] = c;
      ncell = std::max(ncell, c + 1);
    }
    cells[size_t(p)] = ncell;
    if (patch_scratch_bytes(long(t.size()), kind_rows, ncell) > kPatchScratchBytes) {
      Attempt a;
      for (long i = 0; i < n && a.too_big_point < 0; ++i)
        if (point_patch[size_t(i)] == p) a.too_big_point = int(i);
      return a;
    }
  }

  // Patches coloured greedily in patch order: two patches that share a moving point differ.
  std::vector<long> point_off(size_t(n) + 1, 0);
  for (const auto& t : tables)
    for (int i : t)
      if (movable[i]) ++point_off[size_t(i) + 1];
  for (long i = 0; i < n; ++i) point_off[size_t(i) + 1] += point_off[size_t(i)];
  std::vector<long> point_patches(static_cast<size_t>(point_off[size_t(n)]));
  {
    std::vector<long> fill(point_off.begin(), point_off.end() - 1);
    for (long p = 0; p < np; ++p)
      for (int i : tables[size_t(p)])
        if (movable[i]) point_patches[size_t(fill[size_t(i)]++)] = p;
  }
  std::vector<int> patch_colour(size_t(np), 0);
  std::vector<long> seen_by;  // seen_by[c] == p: colour c is taken by a neighbour of patch p
  int ncolours = 0;
  for (long p = 0; p < np; ++p) {
    for (int i : tables[size_t(p)]) {
      if (!movable[i]) continue;
      for (long k = point_off[size_t(i)]; k < point_off[size_t(i) + 1]; ++k) {
        const long q = point_patches[size_t(k)];
        if (q < p) seen_by[size_t(patch_colour[size_t(q)])] = p;
      }
    }
    int c = 0;
    while (c < ncolours && seen_by[size_t(c)] == p) ++c;
    patch_colour[size_t(p)] = c;
    if (c == ncolours) {
      ++ncolours;
      seen_by.push_back(-1);
    }
  }

  // Sweep order: patches by colour, then index; cells numbered in that order.
  std::vector<long> order(static_cast<size_t>(np));
  out.colour_begin.assign(size_t(ncolours) + 1, 0);
  for (long p = 0; p < np; ++p) ++out.colour_begin[size_t(patch_colour[size_t(p)]) + 1];
  for (int c = 0; c < ncolours; ++c) out.colour_begin[size_t(c) + 1] += out.colour_begin[size_t(c)];
  {
    std::vector<long> fill(out.colour_begin.begin(), out.colour_begin.end() - 1);
    for (long p = 0; p < np; ++p) order[size_t(fill[size_t(patch_colour[size_t(p)])]++)] = p;
  }
  out.cell_begin.assign(size_t(np) + 1, 0);
  out.table_begin.assign(size_t(np) + 1, 0);
  std::vector<long> first_cell(static_cast<size_t>(np));
  for (long s = 0; s < np; ++s) {
    const long p = order[size_t(s)];
    first_cell[size_t(p)] = out.cell_begin[size_t(s)];
    out.cell_begin[size_t(s) + 1] = out.cell_begin[size_t(s)] + cells[size_t(p)];
    out.table_begin[size_t(s) + 1] = out.table_begin[size_t(s)] + long(tables[size_t(p)].size());
    out.table.insert(out.table.end(), tables[size_t(p)].begin(), tables[size_t(p)].end());
    out.max_cells = std::max(out.max_cells, cells[size_t(p)]);
  }
  out.row_cell.resize(size_t(nr));
  for (long r = 0; r < nr; ++r)
    out.row_cell[size_t(r)] = row_patch[size_t(r)] < 0 ? -1 : int(first_cell[size_t(row_patch[size_t(r)])] + row_colour[size_t(r)]);
  Attempt a;
  a.patches = std::move(out);
  return a;
}

}  // namespace

long patch_scratch_bytes(long points, const std::array<long, kRowKinds>& rows, long cells) {
  long b = 2 * round8(points * long(sizeof(Vec3))) + round8(points * long(sizeof(real))) +
           round8((cells + 1) * kRowKinds * long(sizeof(int)));
  long all = 0;
  for (int k = 0; k < kRowKinds; ++k) {
    b += round8(rows[size_t(k)] * packed_row_size(k));
    all += rows[size_t(k)];
  }
  return b + round8(all * long(sizeof(real)));
}

SweepPatches build_sweep_patches(const std::vector<Row>& rows, const std::vector<Vec3>& x,
                                 const std::vector<char>& movable, int patch_points) {
  // The moving points in Morton order of their positions (ties to the lower index: unique keys).
  Vec3 lo = x.empty() ? Vec3{} : x[0], hi = lo;
  for (const Vec3& p : x)
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
    }
  const real extent = std::max(hi.x - lo.x, std::max(hi.y - lo.y, hi.z - lo.z));
  std::vector<uint64_t> keys;
  for (size_t i = 0; i < x.size(); ++i)
    if (movable[i]) keys.push_back(uint64_t(morton30(x[i], lo, extent)) << 32 | uint64_t(i));
  std::sort(keys.begin(), keys.end());
  std::vector<int> by_rank(keys.size());
  for (size_t k = 0; k < keys.size(); ++k) by_rank[k] = int(keys[k] & 0xffffffffu);
  for (int P = std::max(1, patch_points);; P /= 2) {
    Attempt a = build_for(rows, by_rank, movable, P);
    if (a.patches) return std::move(*a.patches);
    if (P == 1)
      throw InputError("point " + std::to_string(a.too_big_point) +
                       ": its constraint rows do not fit one patch of the sweep (" +
                       std::to_string(kPatchScratchBytes) + " bytes)");
  }
}

}  // namespace weft
