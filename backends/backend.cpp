#include "backends/backend.hpp"

#include "core/kokkos_compat.hpp"

#include <algorithm>
#include <cctype>
#include <thread>

namespace weft {

std::vector<std::string> describe_cuda_devices();  // backends/cuda_devices.cpp; empty without CUDA

const char* backend_name(Backend b) {
  switch (b) {
    case Backend::Serial: return "serial";
    case Backend::OpenMP: return "openmp";
    case Backend::Cuda: return "cuda";
  }
  return "?";
}

std::optional<Backend> parse_backend(const std::string& s) {
  std::string l(s);
  std::transform(l.begin(), l.end(), l.begin(), [](unsigned char c) { return std::tolower(c); });
  for (Backend b : {Backend::Serial, Backend::OpenMP, Backend::Cuda})
    if (l == backend_name(b)) return b;
  return std::nullopt;
}

std::vector<Backend> compiled_backends() {
  std::vector<Backend> r;
#ifdef KOKKOS_ENABLE_SERIAL
  r.push_back(Backend::Serial);
#endif
#ifdef KOKKOS_ENABLE_OPENMP
  r.push_back(Backend::OpenMP);
#endif
#ifdef KOKKOS_ENABLE_CUDA
  r.push_back(Backend::Cuda);
#endif
  return r;
}

bool backend_compiled(Backend b) {
  const auto all = compiled_backends();
  return std::find(all.begin(), all.end(), b) != all.end();
}

Backend default_backend() {
  for (Backend b : {Backend::Cuda, Backend::OpenMP, Backend::Serial})
    if (backend_compiled(b)) return b;
  return Backend::Serial;
}

Runtime::Runtime(int threads, int device) : owns_(!Kokkos::is_initialized()) {
  if (owns_) compat::initialize(threads, device);
}
Runtime::~Runtime() {
  if (owns_) Kokkos::finalize();
}

std::vector<std::string> describe_devices() {
  std::vector<std::string> r;
  r.push_back("host: " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads");
#ifdef KOKKOS_ENABLE_OPENMP
  if (Kokkos::is_initialized())
    r.push_back("openmp: " + std::to_string(compat::concurrency<Kokkos::OpenMP>()) + " threads");
#endif
  for (auto& s : describe_cuda_devices()) r.push_back(s);
  return r;
}

}  // namespace weft
