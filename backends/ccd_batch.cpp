#include "backends/ccd_batch.hpp"

#include "backends/dispatch.hpp"
#include "backends/on_backend.hpp"

namespace weft {

std::vector<CcdResult> ccd_batch(Backend b, CcdKind kind, const std::vector<Vec3>& rows, real ms,
                                 const CcdSettings& settings) {
  return with_backend(b, [&](auto on) { return OnBackend<typename decltype(on)::exec>::ccd_batch(kind, rows, ms, settings); });
}

}  // namespace weft
