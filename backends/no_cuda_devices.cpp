// Builds without CUDA list no CUDA devices.
#include <string>
#include <vector>

namespace weft {
std::vector<std::string> describe_cuda_devices() { return {}; }
long device_memory_used_bytes() { return -1; }
}  // namespace weft
