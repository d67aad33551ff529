// CUDA device listing for `weft info`; compiled only in CUDA builds.
#include <cuda_runtime.h>

#include <string>
#include <vector>

namespace weft {

std::vector<std::string> describe_cuda_devices() {
  std::vector<std::string> r;
  int n = 0;
  if (cudaGetDeviceCount(&n) != cudaSuccess) {
    cudaGetLastError();
    r.push_back("cuda: no usable CUDA device or driver");
    return r;
  }
  for (int i = 0; i < n; ++i) {
    cudaDeviceProp p{};
    if (cudaGetDeviceProperties(&p, i) != cudaSuccess) continue;
    r.push_back("cuda device " + std::to_string(i) + ": " + p.name + ", compute capability " +
                std::to_string(p.major) + "." + std::to_string(p.minor) + ", " +
                std::to_string(p.totalGlobalMem >> 20) + " MiB");
  }
  if (n == 0) r.push_back("cuda: no device found");
  return r;
}

long device_memory_used_bytes() {
  size_t free_b = 0, total_b = 0;
  if (cudaMemGetInfo(&free_b, &total_b) != cudaSuccess) { cudaGetLastError(); return -1; }
  return long(total_b - free_b);
}

}  // namespace weft
