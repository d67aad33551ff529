// What weft runs on one execution space, behind the run-time backend choice (backends/dispatch.hpp).
// Declarations only: backends/<backend>.cpp instantiate OnBackend<Exec> (backends/on_backend_impl.hpp) for
// their execution space, so each backend's kernels are compiled once, in one translation unit, and the code
// that dispatches does not compile them again.
#pragma once
#include "backends/intersection_counter.hpp"
#include "backends/simulation.hpp"
#include "collision/body_cleaning_result.hpp"
#include "collision/ccd.hpp"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace weft {

template <class Exec>
struct OnBackend {
  static std::unique_ptr<Simulation> make_simulation(const Scene& scene);
  static BodyCleaning clean_body(const Scene& scene, const CleaningSettings& settings);
  static std::vector<CcdResult> ccd_batch(CcdKind kind, const std::vector<Vec3>& rows, real ms,
                                          const CcdSettings& settings);
  static std::unique_ptr<IntersectionCounter> make_intersection_counter(const std::string& name,
                                                                        const std::vector<std::array<int, 3>>& tris);
};

}  // namespace weft
