// The Gauss-Seidel sweep by patches (docs/solver.md, "The sweep by patches"). The moving points are cut
// into compact patches of a few dozen, grown over the mesh from seeds in Morton order of the initial
// positions; a row belongs to the first patch among its points' (a row that moves no point is left out). A patch's rows are coloured among themselves into cells (rows of a cell
// share no moving point), and the patches are coloured so that no two of one patch colour share a moving
// point. A sweep is then one launch per patch colour, one team per patch, with the patch's points and rows
// in the team's scratch memory and a team barrier between its cells: a handful of device-wide levels where
// colouring the whole cloth needs one per colour. Built on the host from the input alone, so the order, and
// the bits, are the same on every backend.
#pragma once
#include "constraints/rows.hpp"

#include <array>
#include <vector>

namespace weft {

struct SweepPatches {
  int patch_points = 0;                   // moving points per patch (the setting, halved until patches fit)
  std::vector<long> colour_begin;         // patches of patch colour c: [colour_begin[c], colour_begin[c + 1])
  std::vector<long> cell_begin;           // patch p (in sweep order) has the cells [cell_begin[p], cell_begin[p + 1])
  std::vector<long> table_begin;          // patch p's points: table[table_begin[p] .. table_begin[p + 1])
  std::vector<int> table;                 // cloth points, ascending within a patch
  std::vector<int> row_cell;              // per row: its cell, numbered in sweep order (-1: moves no point)
  std::vector<std::array<int, 5>> local;  // per row: its points' places in its patch's table (-1: unused)
  int max_cells = 0;                      // cells of the patch with the most

  int patch_colours() const { return int(colour_begin.size()) - 1; }
  long patches() const { return long(cell_begin.size()) - 1; }
  long cells() const { return cell_begin.back(); }
};

// Scratch memory one patch may use on every backend: its points (position, start of the substep, inverse
// mass), its rows and their lambdas, its cells' offsets. Below CUDA's 48 KB a block, with room for Kokkos'
// own share and for more than one team on a multiprocessor.
inline constexpr long kPatchScratchBytes = 40 * 1024;

// Scratch bytes of a patch with `points` points, rows[K] rows of kind K and `cells` cells (each allocation
// rounded up to 8 bytes, as Kokkos' scratch allocator does).
long patch_scratch_bytes(long points, const std::array<long, kRowKinds>& rows, long cells);

// The patches of `rows` over points at positions x (movable[i]: point i moves), with patch_points moving
// points per patch (>= 1), halved until every patch fits kPatchScratchBytes. Throws InputError when one
// point's rows alone do not fit.
SweepPatches build_sweep_patches(const std::vector<Row>& rows, const std::vector<Vec3>& x,
                                 const std::vector<char>& movable, int patch_points);

}  // namespace weft
