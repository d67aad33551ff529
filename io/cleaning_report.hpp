// The JSON report of `weft check` (docs/solvability.md): settings, reserved thickness, and per frame what
// was found, what moved and what is left.
#pragma once
#include "collision/body_cleaning_result.hpp"

#include <array>
#include <string>
#include <vector>

namespace weft::io {

// `cloth_pairs`: the cloth's triangle pairs that intersect at its start (weft check). Written under a
// temporary name and renamed into place; I/O failures throw std::system_error.
void write_cleaning_report(const std::string& path, const std::string& scene, const CleaningSettings& settings,
                           const BodyCleaning& result, const std::vector<std::array<int, 2>>& cloth_pairs = {});

}  // namespace weft::io
