// OnBackend's definitions; included only by backends/<backend>.cpp, which instantiate them.
#pragma once
#include "backends/intersection_counter_on.hpp"
#include "backends/on_backend.hpp"
#include "backends/simulation_on.hpp"
#include "collision/body_cleaning.hpp"
#include "collision/ccd_batch.hpp"

namespace weft {

template <class Exec>
std::unique_ptr<Simulation> OnBackend<Exec>::make_simulation(const Scene& scene) {
  return std::make_unique<SimulationOn<Exec>>(scene);
}

template <class Exec>
BodyCleaning OnBackend<Exec>::clean_body(const Scene& scene, const CleaningSettings& settings) {
  return clean_body_on<Exec>(scene, settings);
}

template <class Exec>
std::vector<CcdResult> OnBackend<Exec>::ccd_batch(CcdKind kind, const std::vector<Vec3>& rows, real ms,
                                                  const CcdSettings& settings) {
  return ccd_batch_on<Exec>(kind, rows, ms, settings);
}

template <class Exec>
std::unique_ptr<IntersectionCounter> OnBackend<Exec>::make_intersection_counter(
    const std::string& name, const std::vector<std::array<int, 3>>& tris) {
  return std::make_unique<IntersectionCounterOn<Exec>>(name, tris);
}

}  // namespace weft
