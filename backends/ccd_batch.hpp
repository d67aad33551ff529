// CCD queries in a batch (collision/ccd_batch.hpp) on the backend chosen at run time.
#pragma once
#include "backends/backend.hpp"
#include "collision/ccd.hpp"

#include <vector>

namespace weft {

// rows: 8 positions per query, as ccd_batch takes them; one result per query. Throws std::runtime_error when
// `b` is not compiled in.
std::vector<CcdResult> ccd_batch(Backend b, CcdKind kind, const std::vector<Vec3>& rows, real ms,
                                 const CcdSettings& settings = {});

}  // namespace weft
