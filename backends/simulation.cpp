#include "backends/simulation.hpp"

#include <Kokkos_Core.hpp>
#include <stdexcept>

namespace weft {

std::unique_ptr<Simulation> make_simulation_serial(const Scene& s);
std::unique_ptr<Simulation> make_simulation_openmp(const Scene& s);
std::unique_ptr<Simulation> make_simulation_cuda(const Scene& s);

std::unique_ptr<Simulation> make_simulation(Backend b, const Scene& scene) {
  switch (b) {
#ifdef KOKKOS_ENABLE_SERIAL
    case Backend::Serial: return make_simulation_serial(scene);
#endif
#ifdef KOKKOS_ENABLE_OPENMP
    case Backend::OpenMP: return make_simulation_openmp(scene);
#endif
#ifdef KOKKOS_ENABLE_CUDA
    case Backend::Cuda: return make_simulation_cuda(scene);
#endif
    default: break;
  }
  throw std::runtime_error(std::string("this build of weft has no ") + backend_name(b) + " backend");
}

}  // namespace weft
