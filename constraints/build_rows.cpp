#include "constraints/build_rows.hpp"

namespace weft {

int row_particles(const Row& r, int (&out)[8]) {
  for (int k = 0; k < r.n; ++k) out[k] = r.idx[k];
  return r.n;
}

std::vector<Row> build_rows(const Scene& s, const std::vector<int>& collider_first_vertex) {
  const Constraints& c = s.constraints;
  std::vector<Row> rows;
  rows.reserve(c.size() + c.fem.size());
  auto set_dm = [](Row& r, const real (&dm)[4]) {
    for (int k = 0; k < 4; ++k) r.data[k] = dm[k];
  };
  for (const auto& d : c.distance) {
    Row r; r.kind = kRowDistance; r.n = 2; r.idx[0] = d.a; r.idx[1] = d.b; r.rest = d.rest; r.m = d.m;
    rows.push_back(r);
  }
  for (const auto& b : c.bend) {
    Row r; r.kind = kRowBend; r.n = 4; r.idx[0] = b.o0; r.idx[1] = b.o1; r.idx[2] = b.e0; r.idx[3] = b.e1;
    r.rest = b.rest_rad; r.m = b.m;
    rows.push_back(r);
  }
  for (const auto& t : c.triarap) {
    Row r; r.kind = kRowTriarap; r.n = 3; r.idx[0] = t.p0; r.idx[1] = t.p1; r.idx[2] = t.p2; set_dm(r, t.dm_inv);
    r.m = t.m;
    if (t.normalized) {  // Vellum's "norm" variant: compliance per unit rest area
      r.m.compliance /= t.area;
      r.m.compress_compliance /= t.area;
    }
    rows.push_back(r);
  }
  for (const auto& p : c.pin) {
    Row r; r.kind = kRowPin; r.n = 1; r.idx[0] = p.p; r.target = p.target; r.rest = p.rest; r.m = p.m;
    r.data[0] = p.goal.x; r.data[1] = p.goal.y; r.data[2] = p.goal.z;
    rows.push_back(r);
  }
  for (const auto& a : c.attach) {
    Row r; r.kind = kRowAttach; r.n = 1; r.idx[0] = a.p; r.rest = a.rest; r.m = a.m;
    const auto& tri = s.colliders[a.collider].triangles[a.tri];
    for (int k = 0; k < 3; ++k) r.cidx[k] = collider_first_vertex[a.collider] + tri[k];
    r.data[0] = a.u; r.data[1] = a.v;
    rows.push_back(r);
  }
  for (const auto& q : c.ptprim) {
    Row r; r.kind = kRowPtPrim; r.n = 1 + q.nt; r.idx[0] = q.p; r.rest = q.rest; r.m = q.m;
    for (int k = 0; k < q.nt; ++k) { r.idx[k + 1] = q.t[k]; r.data[k] = q.w[k]; }
    rows.push_back(r);
  }
  for (const auto& f : c.fem) {
    Row r; r.n = 3; r.idx[0] = f.p0; r.idx[1] = f.p1; r.idx[2] = f.p2; set_dm(r, f.dm_inv);
    r.kind = kRowFemDeviatoric;
    r.m = {f.dev_compliance, f.dev_compliance, f.damping_ratio};
    rows.push_back(r);
    r.kind = kRowFemHydrostatic;
    r.rest = f.gamma;
    r.m = {f.hyd_compliance, f.hyd_compliance, f.damping_ratio};
    rows.push_back(r);
  }
  return rows;
}

}  // namespace weft
