#include "constraints/vellum_cloth.hpp"

#include "constraints/bend.hpp"
#include "constraints/fem_membrane.hpp"
#include "constraints/triarap.hpp"
#include "core/topology.hpp"

#include <algorithm>

namespace weft {

int add_cloth_piece(Scene& s, const std::vector<Vec3>& x, const std::vector<std::array<int, 3>>& tris,
                    const ClothMaterial& mat) {
  ClothPoints& p = s.points;
  const int first = int(p.size());
  const int piece = p.piece.empty() ? 0 : p.piece.back() + 1;
  const std::vector<real> mass = lumped_masses(x, tris, mat.density);
  for (size_t i = 0; i < x.size(); ++i) {
    p.position.push_back(x[i]);
    p.velocity.push_back({});
    p.mass.push_back(mass[i]);
    p.thickness.push_back(mat.thickness);
    p.friction.push_back(mat.friction);
    p.dynamic_friction.push_back(mat.dynamic_friction);
    p.layer.push_back(mat.layer);
    p.stopped.push_back(0);
    p.piece.push_back(piece);
  }
  for (const auto& t : tris) s.triangles.push_back({first + t[0], first + t[1], first + t[2]});

  const Topology topo = build_topology(tris);
  const XpbdMaterial stretch = xpbd_material(mat.stretch_stiffness, mat.compress_stiffness, mat.stretch_damping);
  Constraints& c = s.constraints;
  switch (mat.stretch) {
    case StretchModel::Distance:
      for (const auto& e : topo.edges)
        c.distance.push_back({first + e[0], first + e[1], norm(x[e[1]] - x[e[0]]), stretch});
      break;
    case StretchModel::Triarap:
    case StretchModel::TriarapNorm:
      for (const auto& t : tris) {
        TriarapConstraint r{first + t[0], first + t[1], first + t[2], {0, 0, 0, 0}, 0,
                            mat.stretch == StretchModel::TriarapNorm, stretch};
        triarap_rest(x[t[0]], x[t[1]], x[t[2]], r.dm_inv, r.area);
        c.triarap.push_back(r);
      }
      break;
    case StretchModel::Fem: {
      real mu = 0, lambda = 0;
      fem_lame(mat.young, mat.poisson, mu, lambda);
      for (const auto& t : tris) {
        FemConstraint f{first + t[0], first + t[1], first + t[2], {0, 0, 0, 0}, 0, 0, 0, 0, mat.stretch_damping};
        triarap_rest(x[t[0]], x[t[1]], x[t[2]], f.dm_inv, f.area);
        f.dev_compliance = 1 / (mu * mat.fabric_thickness * f.area);
        f.hyd_compliance = 1 / (lambda * mat.fabric_thickness * f.area);
        f.gamma = fem_gamma(mu, lambda);
        c.fem.push_back(f);
      }
      break;
    }
  }
  if (mat.bend_stiffness > 0) {
    const XpbdMaterial bend = xpbd_material(mat.bend_stiffness, -1, mat.bend_damping);
    for (const auto& q : topo.bend_quads)
      c.bend.push_back({first + q[0], first + q[1], first + q[2], first + q[3],
                        bend_rest_angle(x[q[0]], x[q[1]], x[q[2]], x[q[3]]), bend});
  }
  return first;
}

int add_pin_targets(Scene& s, const Animation& track) {
  Animation& a = s.pin_targets;
  const int first = a.empty() ? 0 : int(a.frames[0].size());
  if (track.empty()) return first;
  const size_t frames = std::max(a.frames.size(), track.frames.size());
  if (a.empty()) a.frames.resize(1);
  while (a.frames.size() < frames) a.frames.push_back(a.frames.back());  // hold the last frame
  for (size_t f = 0; f < frames; ++f) {
    const auto& goals = track.frames[std::min(f, track.frames.size() - 1)];
    a.frames[f].insert(a.frames[f].end(), goals.begin(), goals.end());
  }
  return first;
}

void pin_to_targets(Scene& s, const std::vector<int>& point, const std::vector<int>& target, bool hard,
                    const XpbdMaterial& m) {
  for (size_t i = 0; i < point.size(); ++i) {
    if (hard) {
      s.kinematic_point.push_back(point[i]);
      s.kinematic_target.push_back(target[i]);
    } else {
      s.constraints.pin.push_back({point[i], s.points.position[size_t(point[i])], target[i], 0, m});
    }
  }
}

}  // namespace weft
