// `weft info`: versions, backends, devices and the named schedules (scene/schedules.hpp); `weft info FILE`:
// what a scene or cache file holds.
#include "apps/cli.hpp"
#include "constraints/build_stretch_limits.hpp"
#include "core/hash.hpp"
#include "core/kokkos_compat.hpp"
#include "io/cache_file.hpp"
#include "io/hdf5_util.hpp"
#include "io/scene_file.hpp"
#include "scene/schedules.hpp"
#include "weft_version.hpp"

#include <iostream>
#include <sstream>

namespace weft::cli {

namespace {

std::string vec_string(Vec3 v) {
  std::ostringstream s;
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

std::string stretch_limits_name(int levels) {
  if (levels <= 0) return "off";
  std::string s;
  for (int k = 1; k <= levels; ++k) s += (k > 1 ? ", " : "") + std::to_string(stretch_limit_hops(k));
  return s + " hops";
}

// fem_rows: the scene has FEM membrane rows, which run without Chebyshev acceleration (a cache does not say).
void print_settings(const SolverSettings& s, bool fem_rows = false) {
  const CollisionSettings& c = s.collision;
  std::ostringstream tethers;
  if (s.tether_stretch > 0) tethers << s.tether_stretch;
  else tethers << "off";
  std::ostringstream chebyshev;  // the ccd model ignores the setting (docs/solver.md)
  if (s.chebyshev_rho <= 0) chebyshev << "off";
  else if (c.contact_model == ContactModel::Ccd) chebyshev << "off (ccd model)";
  else if (fem_rows) chebyshev << "off (FEM membrane rows)";
  else chebyshev << "rate " << s.chebyshev_rho << " after " << s.chebyshev_delay << " iterations";
  std::cout << "settings: frames " << s.frame_start << "-" << s.frame_end << " at " << s.fps << " fps, substeps "
            << s.substeps << ", iterations " << s.iterations << ", collision passes " << s.collision_passes
            << ", smoothing iterations " << s.smoothing_iterations << ", Chebyshev " << chebyshev.str() << "\n"
            << "  gravity " << vec_string(s.gravity) << ", wind " << vec_string(s.wind) << ", velocity damping "
            << s.velocity_damping << "\n"
            << "  self collision " << (c.self_collision ? "on" : "off") << ", friction static " << c.static_friction
            << " dynamic " << c.dynamic_friction << ", layer shock " << c.layer_shock << ", parallel edges "
            << c.parallel_edge_degrees << " degrees\n"
            << "  contact model " << contact_model_name(c.contact_model);
  if (c.contact_model == ContactModel::Proximity)
    std::cout << " (early passes at " << c.early_pass_fraction << " of the points held to less than 1/"
              << 1 + c.early_pass_excess << " of their move, at most "
              << c.max_early_passes << " a substep, " << c.max_collider_early_passes
              << " while a collider pushes; pair refresh " << (c.pair_refresh ? "on" : "off")
              << "; nearest margins " << (c.nearest_margins ? "on" : "off") << "; predicted reference "
              << (c.predicted_reference ? "on" : "off") << "; still tolerance " << c.still_tolerance << ")";
  const char* rows = c.merge_contacts ? " (contacts on the same points merged)" : " (every contact a row)";
  std::cout << "\n"
            << "  impact zone smoothing " << (c.impact_zone_smoothing ? "on" : "off") << " (epsilon "
            << c.impact_zone_epsilon << ", " << c.impact_zone_sweeps << " sweeps), ";
  // The proximity model always sums its contacts Jacobi-style and has no fail-safe or CCD span to show.
  if (c.contact_model == ContactModel::Proximity)
    std::cout << "contacts jacobi" << rows;
  else
    std::cout << "crossing fail-safe " << (c.collision_failsafe ? "on" : "off") << ", contact solver "
              << contact_solver_name(c.contact_solver) << (c.contact_solver == ContactSolver::Jacobi ? rows : "")
              << ", CCD span " << ccd_span_name(c.ccd_span);
  std::cout << ", tethers " << tethers.str() << ", stretch limits " << stretch_limits_name(s.stretch_limits)
            << ", coarse levels ";
  if (s.coarse_levels > 0) std::cout << s.coarse_levels << " (" << s.coarse_iterations << " sweeps each)\n";
  else std::cout << "off\n";
}

void print_scene(const std::string& path) {
  const Scene s = io::read_scene(path);
  const Constraints& c = s.constraints;
  std::cout << path << ": weft scene, format version " << io::kSceneFormatVersion << "\n"
            << "name " << s.name << "\n"
            << "points " << s.points.size() << ", triangles " << s.triangles.size() << "\n"
            << "constraints " << c.size() << ": distance " << c.distance.size() << ", bend " << c.bend.size()
            << ", triarap " << c.triarap.size() << ", pin " << c.pin.size() << ", attach " << c.attach.size()
            << ", ptprim " << c.ptprim.size() << ", fem " << c.fem.size() << "\n"
            << "pin targets " << (s.pin_targets.empty() ? 0 : s.pin_targets.frames[0].size()) << " over "
            << s.pin_targets.frames.size() << " frames, kinematic pins " << s.kinematic_point.size() << "\n";
  for (size_t i = 0; i < s.colliders.size(); ++i) {
    const Collider& col = s.colliders[i];
    std::cout << "collider " << i << " '" << col.name << "': " << col.motion.frames[0].size() << " points, "
              << col.triangles.size() << " triangles, " << col.motion.frames.size() << " frames, thickness "
              << col.thickness << ", friction " << col.friction << "\n";
  }
  std::cout << "needs collisions " << (s.needs_collisions ? "yes" : "no") << "\n";
  print_settings(s.settings, !s.constraints.fem.empty());
}

void print_cache(const std::string& path) {
  const io::CacheReader c(path);
  const io::CacheHeader& h = c.header();
  std::cout << path << ": weft cache, format version " << io::kCacheFormatVersion << "\n"
            << "scene " << h.scene << ", computed by the " << h.backend << " backend\n"
            << "points " << h.points << ", triangles " << h.triangles.size() << "\n";
  if (!h.overrides.empty()) std::cout << "set " << h.overrides << "\n";
  if (c.frame_count() == 0) {
    std::cout << "frames: none\n";
  } else {
    const int last = c.frames().back();
    double seconds = 0;
    for (const FrameStats& fs : c.stats()) seconds += fs.seconds;
    std::cout << "frames " << c.frames().front() << "-" << last << " (" << c.frame_count() << " stored, "
              << (last >= h.settings.frame_end ? "complete" : "run planned to " + std::to_string(h.settings.frame_end))
              << "), " << seconds << " s of simulation\n";
  }
  print_settings(h.settings);
  std::cout << "hash " << hash_hex(io::cache_hash(c)) << "\n";
}

int describe_file(const std::string& path) {
  try {
    std::string kind;
    {
      const io::h5::File f = io::h5::File::open(path);
      kind = io::h5::format_of(f);
    }
    if (kind == io::kSceneFormat)
      print_scene(path);
    else if (kind == io::kCacheFormat)
      print_cache(path);
    else
      throw Error(path + ": not a weft scene or cache (" +
                      (kind.empty() ? std::string("no weft_format attribute") : "weft_format is '" + kind + "'") + ")",
                  2);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(e.what(), 2);
  }
  return 0;
}

void add_info(CLI::App& app, const GlobalOptions& g, Action& run) {
  static std::string file;
  auto* cmd = app.add_subcommand("info", "print versions, enabled backends, devices and named schedules, or what a .h5 "
                                         "file holds");
  cmd->add_option("file", file, "a weft scene or cache (.h5): print its kind, version, counts, frames, settings");
  cmd->callback([&g, &run] {
    run = [&g] {
      if (!file.empty()) return describe_file(file);
      const Backend b = resolve_backend(g);
      Runtime rt(g.threads);
      std::cout << "weft " << WEFT_VERSION << "\n";
      std::cout << "kokkos " << compat::kokkos_version_string() << "\n";
      std::cout << "backends:";
      for (Backend c : compiled_backends()) std::cout << " " << backend_name(c);
      std::cout << "\nselected backend: " << backend_name(b) << "\n";
      for (const auto& line : describe_devices()) std::cout << line << "\n";
      // The named schedules, for the report scripts (bench/reports/error_vs_time.py) to take from here.
      for (const Schedule& s : kSchedules)
        std::cout << "schedule " << s.name << ": substeps " << s.substeps << ", iterations " << s.iterations
                  << ", collision passes " << s.collision_passes << "\n";
      return 0;
    };
  });
}

const Register reg("info", add_info);

}  // namespace
}  // namespace weft::cli
