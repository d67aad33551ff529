// The solvability check instantiated for Kokkos::OpenMP.
#include "collision/body_cleaning.hpp"

namespace weft {
BodyCleaning clean_body_openmp(const Scene& s, const CleaningSettings& cs) { return clean_body_on<Kokkos::OpenMP>(s, cs); }
}  // namespace weft
