// The animation solvability check (collision/body_cleaning.hpp) on the backend chosen at run time.
#pragma once
#include "backends/backend.hpp"
#include "collision/body_cleaning_result.hpp"

namespace weft {

// Throws InputError for an invalid scene, std::runtime_error when `b` is not compiled in.
BodyCleaning clean_body(Backend b, const Scene& scene, const CleaningSettings& settings = {});

}  // namespace weft
