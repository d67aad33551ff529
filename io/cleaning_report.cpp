#include "io/cleaning_report.hpp"

#include "io/trimesh.hpp"

#include <nlohmann/json.hpp>

namespace weft::io {

void write_cleaning_report(const std::string& path, const std::string& scene, const CleaningSettings& settings,
                           const BodyCleaning& result, const std::vector<std::array<int, 2>>& cloth_pairs) {
  nlohmann::json frames = nlohmann::json::array();
  for (const FrameCleaning& f : result.frames)
    frames.push_back({{"frame", f.frame},
                      {"intersections_before", f.intersections_before},
                      {"interior_before", f.interior_before},
                      {"gap_violations_before", f.gap_violations_before},
                      {"self_steps", f.self_steps},
                      {"gap_iterations", f.gap_iterations},
                      {"points_moved", f.points_moved},
                      {"max_displacement", f.max_displacement},
                      {"intersections_left", f.intersections_left},
                      {"interior_left", f.interior_left},
                      {"gap_violations_left", f.gap_violations_left},
                      {"clean", f.clean()}});
  const nlohmann::json j = {
      {"scene", scene},
      {"settings",
       {{"reach", settings.reach},
        {"step", settings.step},
        {"max_steps", settings.max_steps},
        {"max_iterations", settings.max_iterations},
        {"overshoot", settings.overshoot}}},
      {"reserved", {{"points", result.reserved_points}, {"max", result.max_reserved}}},
      {"frames", frames},
      {"points_moved", result.points_moved()},
      {"max_displacement", result.max_displacement()},
      {"violations_left", result.violations_left()},
      {"cloth_intersections_at_start", cloth_pairs},
      {"clean", result.clean() && cloth_pairs.empty()},
      {"summary", cleaning_summary(result, long(cloth_pairs.size()))}};
  write_file_atomically(path, [&](std::ostream& out) { out << j.dump(2) << "\n"; });
}

}  // namespace weft::io
