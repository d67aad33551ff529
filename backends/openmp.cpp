// What weft runs on Kokkos::OpenMP (backends/on_backend.hpp): the solver, the solvability check, CCD batches,
// intersection counts. One translation unit, so that the templates they share (LBVH, sort, reductions) are
// instantiated for this backend once.
#include "backends/on_backend_impl.hpp"

namespace weft {
template struct OnBackend<Kokkos::OpenMP>;
}  // namespace weft
