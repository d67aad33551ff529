// `weft run` as a function, for commands that run a scene as one of their steps (`weft demo`).
#pragma once
#include "apps/cli.hpp"

#include <string>
#include <vector>

namespace weft::cli {

struct RunOptions {
  std::string scene;
  int res = 0;
  std::string frames;
  std::string schedule;
  int substeps = -1, iterations = -1, collision_passes = -1, smoothing = -1;
  bool no_impact_zones = false, no_failsafe = false;  // switch off impact-zone smoothing, the crossing fail-safe
  std::string self_collision;  // "on" | "off" | "" (the scene's setting)
  std::string contact_model;   // "proximity" | "ccd" | "" (the scene's setting)
  std::string pair_refresh;    // "on" | "off" | "" (the scene's setting)
  std::string contact_solver;  // "gauss-seidel" | "jacobi" | "" (the scene's setting)
  std::string ccd_span;        // "substep" | "pass" | "" (the scene's setting)
  std::string tethers;         // tether stretch, "" (the scene's setting)
  std::vector<std::string> set;  // "name=value" settings (io/scene_overrides.hpp), applied after --schedule
  bool hash = false, quiet = false;
  std::string output, geo_dir;
  std::string like, geo_format;  // with geo_dir: frames as copies of `like`; "geo" | "bgeo" | "" (like's kind)
  bool resume = false;
  bool clean = false;  // run the solvability check on the colliders first
};

// Simulates o.scene as `weft run` does (cache, .geo sequence, resume, progress, SIGINT); returns the exit code.
int run_scene(const GlobalOptions& g, const RunOptions& o);

}  // namespace weft::cli
