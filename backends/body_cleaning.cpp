#include "backends/body_cleaning.hpp"

#include "collision/body_cleaning_input.hpp"

#include <stdexcept>

namespace weft {

BodyCleaning clean_body_serial(const Scene& s, const CleaningSettings& cs);
BodyCleaning clean_body_openmp(const Scene& s, const CleaningSettings& cs);
BodyCleaning clean_body_cuda(const Scene& s, const CleaningSettings& cs);

BodyCleaning clean_body(Backend b, const Scene& scene, const CleaningSettings& settings) {
  validate_scene(scene);
  check_collider_orientation(scene);
  switch (b) {
#ifdef KOKKOS_ENABLE_SERIAL
    case Backend::Serial: return clean_body_serial(scene, settings);
#endif
#ifdef KOKKOS_ENABLE_OPENMP
    case Backend::OpenMP: return clean_body_openmp(scene, settings);
#endif
#ifdef KOKKOS_ENABLE_CUDA
    case Backend::Cuda: return clean_body_cuda(scene, settings);
#endif
    default: break;
  }
  throw std::runtime_error(std::string("this build of weft has no ") + backend_name(b) + " backend");
}

}  // namespace weft
