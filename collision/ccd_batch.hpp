// Many CCD queries of one kind at once, one thread each.
#pragma once
#include "collision/ccd.hpp"
#include "core/device_copy.hpp"

#include <Kokkos_Core.hpp>
#include <vector>

namespace weft {

template <class Mem>
struct CcdBatch {
  CcdKind kind;
  Kokkos::View<const Vec3*, Mem> rows;
  real ms;
  CcdSettings s;
  Kokkos::View<CcdResult*, Mem> out;
  KOKKOS_INLINE_FUNCTION void operator()(long q) const {
    const long r = 8 * q;
    out(q) = kind == CcdKind::VertexFace
                 ? ccd_vertex_face(rows(r), rows(r + 1), rows(r + 2), rows(r + 3), rows(r + 4), rows(r + 5),
                                   rows(r + 6), rows(r + 7), ms, s)
                 : ccd_edge_edge(rows(r), rows(r + 1), rows(r + 2), rows(r + 3), rows(r + 4), rows(r + 5),
                                 rows(r + 6), rows(r + 7), ms, s);
  }
};

// rows: 8 positions per query, in the argument order of ccd_vertex_face / ccd_edge_edge (the four start
// positions, then the four end positions); out: one result per query.
template <class Exec>
void ccd_batch(const Exec& exec, CcdKind kind, const Kokkos::View<const Vec3*, typename Exec::memory_space>& rows,
               real ms, const CcdSettings& settings,
               const Kokkos::View<CcdResult*, typename Exec::memory_space>& out) {
  const long n = static_cast<long>(rows.extent(0) / 8);
  Kokkos::parallel_for("weft::ccd_batch", Kokkos::RangePolicy<Exec>(exec, 0, n),
                       CcdBatch<typename Exec::memory_space>{kind, rows, ms, settings, out});
}

// The same from host rows to host results, on a default instance of Exec.
template <class Exec>
std::vector<CcdResult> ccd_batch_on(CcdKind kind, const std::vector<Vec3>& rows, real ms, const CcdSettings& settings) {
  using Mem = typename Exec::memory_space;
  const Kokkos::View<const Vec3*, Mem> rows_d = upload<Mem>(rows, "weft::ccd_rows");
  Kokkos::View<CcdResult*, Mem> out("weft::ccd_results", rows.size() / 8);
  ccd_batch(Exec(), kind, rows_d, ms, settings, out);
  return to_host(out);
}

}  // namespace weft
