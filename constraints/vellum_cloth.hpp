// Asset configuration as Houdini's Vellum Constraints node does it for cloth: points get mass from an
// area density, thickness, friction and layer; edges get distance constraints (or triangles get triangle
// stretch, or the FEM membrane), interior edges get bend constraints; rest values from the current shape.
#pragma once
#include "scene/scene.hpp"

#include <array>
#include <vector>

namespace weft {

// The material's "stretch" (docs/scene-json.md): distance, triarap, triarapnorm or fem, as Vellum names them.
enum class StretchModel { Distance, Triarap, TriarapNorm, Fem };

struct ClothMaterial {
  real density = 0.1;             // kg/m^2
  real thickness = 0.005;         // m (collision radius, Vellum pscale)
  StretchModel stretch = StretchModel::Distance;
  real stretch_stiffness = 1e10;  // N/m (Vellum's default: practically inextensible)
  real compress_stiffness = -1;   // -1: same as stretch
  real stretch_damping = 0.001;   // damping ratio
  real bend_stiffness = 1e-3;     // N m / rad; 0 disables bending
  real bend_damping = 0.01;
  real young = 1e5, poisson = 0.3, fabric_thickness = 5e-4;  // FEM membrane: Pa, -, m
  real friction = 1, dynamic_friction = 1;  // per-point scales
  int layer = 0;
};

// Appends a cloth piece (points and triangles, in the piece's own numbering) to the scene and configures
// its constraints. Returns the index of the piece's first point in the scene.
int add_cloth_piece(Scene& s, const std::vector<Vec3>& x, const std::vector<std::array<int, 3>>& tris,
                    const ClothMaterial& mat);

// Appends animated goals to Scene::pin_targets: track.frames[f][k] is goal k at frame frame_start + f. The
// shorter of the two animations holds its last frame, so sources of different lengths mix. Returns the
// index of the track's first goal.
int add_pin_targets(Scene& s, const Animation& track);

// Pins points to animated goals as Vellum's pintoanimation does: point[i] follows goal target[i] of
// Scene::pin_targets exactly (hard, kinematic), or is pulled to it by a pin constraint of material m (soft).
void pin_to_targets(Scene& s, const std::vector<int>& point, const std::vector<int>& target, bool hard,
                    const XpbdMaterial& m = {});

}  // namespace weft
