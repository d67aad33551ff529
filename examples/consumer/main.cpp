// An application that runs Kokkos itself and embeds weft: the built-in hanging sheet at resolution 8, frames
// 1 to 4, on the OpenMP backend (Serial in a build without it). The last line is the hash of every frame's
// positions, as `weft run builtin:hanging-sheet --res 8 --frames 1-4 --hash` prints it. Before it, the
// built-in fast collider run twice, its box animated by the scene and streamed frame by frame as a host
// application would hand it over: both give the same bits, or the program fails.
#include <weft/backends/simulation.hpp>
#include <weft/core/hash.hpp>
#include <weft/io/builtin_scenes.hpp>
#include <weft/weft_version.hpp>

#include <Kokkos_Core.hpp>

#include <cstdio>

namespace {

// The hash of frames 1 to 4 of the fast collider, its box from the scene or handed over before each frame.
uint64_t fast_collider(weft::Backend backend, bool streamed) {
  const weft::Scene scene = weft::io::make_builtin_scene("fast-collider", weft::io::BuiltinOptions{4});
  std::unique_ptr<weft::Simulation> sim = weft::make_simulation(backend, scene);
  uint64_t hash = weft::hash_combine(0, sim->hash_positions());
  while (sim->frame() < scene.settings.frame_start + 3) {
    // The box where the application has it at the end of the next frame: here, the scene's own animation.
    const int end = sim->frame() + 1 - scene.settings.frame_start;
    if (streamed) sim->set_collider_frame(0, scene.colliders[0].motion.frames[size_t(end)]);
    sim->step_frame();
    hash = weft::hash_combine(hash, sim->hash_positions());
  }
  return hash;
}

}  // namespace

int main(int argc, char* argv[]) {
  Kokkos::ScopeGuard kokkos(argc, argv);  // the application's Kokkos, initialised before weft's runtime
  weft::Runtime runtime;                  // finds Kokkos running: uses it and leaves finalising to the guard

  const weft::Backend backend =
      weft::backend_compiled(weft::Backend::OpenMP) ? weft::Backend::OpenMP : weft::Backend::Serial;
  const uint64_t animated = fast_collider(backend, false), streamed = fast_collider(backend, true);
  std::printf("fast collider, animated %s, streamed %s\n", weft::hash_hex(animated).c_str(),
              weft::hash_hex(streamed).c_str());
  if (streamed != animated) return 1;

  weft::Scene scene = weft::io::make_builtin_scene("hanging-sheet", weft::io::BuiltinOptions{8});
  scene.settings.frame_start = 1;  // the initial state
  scene.settings.frame_end = 4;
  std::unique_ptr<weft::Simulation> sim = weft::make_simulation(backend, scene);

  uint64_t hash = weft::hash_combine(0, sim->hash_positions());
  while (sim->frame() < scene.settings.frame_end) {
    const weft::FrameStats stats = sim->step_frame();
    hash = weft::hash_combine(hash, sim->hash_positions());
    std::printf("frame %d: max speed %.4f m/s\n", stats.frame, double(stats.max_speed));
  }
  std::printf("weft %s, backend %s, %zu points, weft initialised Kokkos: %s\n", WEFT_VERSION,
              weft::backend_name(backend), scene.points.size(), runtime.owns_kokkos() ? "yes" : "no");
  std::printf("hash %s\n", weft::hash_hex(hash).c_str());
  return 0;
}
