// The solvability check instantiated for Kokkos::Cuda.
#include "collision/body_cleaning.hpp"

namespace weft {
BodyCleaning clean_body_cuda(const Scene& s, const CleaningSettings& cs) { return clean_body_on<Kokkos::Cuda>(s, cs); }
}  // namespace weft
