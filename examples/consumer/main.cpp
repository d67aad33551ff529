// An application that runs Kokkos itself and embeds weft: the built-in hanging sheet at resolution 8, frames
// 1 to 4, on the OpenMP backend (Serial in a build without it). The last line is the hash of every frame's
// positions, as `weft run builtin:hanging-sheet --res 8 --frames 1-4 --hash` prints it.
#include <weft/backends/simulation.hpp>
#include <weft/core/hash.hpp>
#include <weft/io/builtin_scenes.hpp>
#include <weft/weft_version.hpp>

#include <Kokkos_Core.hpp>

#include <cstdio>

int main(int argc, char* argv[]) {
  Kokkos::ScopeGuard kokkos(argc, argv);  // the application's Kokkos, initialised before weft's runtime
  weft::Runtime runtime;                  // finds Kokkos running: uses it and leaves finalising to the guard

  weft::Scene scene = weft::io::make_builtin_scene("hanging-sheet", weft::io::BuiltinOptions{8});
  scene.settings.frame_start = 1;  // the initial state
  scene.settings.frame_end = 4;
  const weft::Backend backend =
      weft::backend_compiled(weft::Backend::OpenMP) ? weft::Backend::OpenMP : weft::Backend::Serial;
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
