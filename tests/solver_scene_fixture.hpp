// Small scenes for solver tests (included by solver_*.hpp topics).
#pragma once
#include "backends/simulation_on.hpp"
#include "constraints/vellum_cloth.hpp"
#include "io/builtin_scenes.hpp"
#include "io/procedural.hpp"
#include "tests/input_error_fixture.hpp"

namespace weft::test {

inline Scene empty_scene(const char* name) {
  Scene s;
  s.name = name;
  s.settings.frame_start = 1;
  s.settings.frame_end = 24;
  return s;
}

// A square sheet of res x res quads, horizontal at height y, with the given material.
inline Scene sheet_scene(int res, const ClothMaterial& mat = {}, real y = 1.0) {
  Scene s = empty_scene("test-sheet");
  const io::Mesh g = io::grid(res, res, {-0.5, y, -0.5}, {1, 0, 0}, {0, 0, 1});
  add_cloth_piece(s, g.x, g.tris, mat);
  s.settings.collision.self_collision = false;  // solver tests: no collision stage
  return s;
}

// Each point's inverse mass as the solver takes it (0 where stopped), for the host-side builders.
inline std::vector<real> inverse_masses(const Scene& s) {
  std::vector<real> w(s.points.size());
  for (size_t i = 0; i < w.size(); ++i) w[i] = s.points.stopped[i] & 1 ? 0.0 : 1 / s.points.mass[i];
  return w;
}

// The 12 x 12 hanging sheet at one substep of 10 plain Gauss-Seidel iterations (Chebyshev off): far from
// converged, it stretches under its own weight.
inline Scene slack_hanging_sheet() {
  Scene s = io::make_builtin_scene("hanging-sheet", {12});
  s.settings.substeps = 1;
  s.settings.iterations = 10;
  s.settings.chebyshev_rho = 0;
  s.settings.coarse_levels = 0;  // the scene's levels would hold it
  return s;
}

template <class Exec>
std::vector<Vec3> run_frames(const Scene& s, int frames, uint64_t* hash = nullptr, FrameStats* last = nullptr) {
  SimulationOn<Exec> sim(s);
  uint64_t h = hash_combine(0, sim.hash_positions());
  for (int f = 0; f < frames; ++f) {
    const FrameStats fs = sim.step_frame();
    h = hash_combine(h, sim.hash_positions());
    if (last) *last = fs;
  }
  if (hash) *hash = h;
  return sim.positions();
}

}  // namespace weft::test
