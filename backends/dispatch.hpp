// The one place that maps a Backend to its Kokkos execution space. with_backend(b, f) calls f(On<Exec>{})
// with Exec the execution space of b, among the backends this build was compiled for:
//
//   with_backend(b, [&](auto on) { return OnBackend<typename decltype(on)::exec>::make_simulation(scene); });
#pragma once
#include "backends/backend.hpp"

#include <Kokkos_Core.hpp>
#include <stdexcept>
#include <string>

namespace weft {

// Names an execution space without making an instance of it (a Kokkos::Cuda instance needs Kokkos running).
template <class Exec>
struct On {
  using exec = Exec;
};

[[noreturn]] inline void throw_backend_not_built(Backend b) {
  throw std::runtime_error(std::string("this build of weft has no ") + backend_name(b) + " backend");
}

// Returns what f returns (the same type for every backend); throws std::runtime_error when this build lacks b.
template <class F>
decltype(auto) with_backend(Backend b, F&& f) {
  switch (b) {
#ifdef KOKKOS_ENABLE_SERIAL
    case Backend::Serial: return f(On<Kokkos::Serial>{});
#endif
#ifdef KOKKOS_ENABLE_OPENMP
    case Backend::OpenMP: return f(On<Kokkos::OpenMP>{});
#endif
#ifdef KOKKOS_ENABLE_CUDA
    case Backend::Cuda: return f(On<Kokkos::Cuda>{});
#endif
    default: break;
  }
  throw_backend_not_built(b);
}

}  // namespace weft
