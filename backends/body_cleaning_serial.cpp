// The solvability check instantiated for Kokkos::Serial.
#include "collision/body_cleaning.hpp"

namespace weft {
BodyCleaning clean_body_serial(const Scene& s, const CleaningSettings& cs) { return clean_body_on<Kokkos::Serial>(s, cs); }
}  // namespace weft
