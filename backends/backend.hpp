// Which Kokkos execution space a run uses, chosen at run time from those this build was compiled for.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace weft {

enum class Backend { Serial, OpenMP, Cuda };

const char* backend_name(Backend b);                        // "serial", "openmp", "cuda"
std::optional<Backend> parse_backend(const std::string& s);  // case-insensitive
std::vector<Backend> compiled_backends();                   // in this build
bool backend_compiled(Backend b);
Backend default_backend();                                  // cuda if compiled, else openmp, else serial

// Kokkos for the lifetime of the object. threads <= 0: Kokkos' default. An application that embeds weft
// and has already initialised Kokkos keeps its own: the object then initialises nothing (threads and device
// are the application's) and leaves finalising to the application.
class Runtime {
 public:
  explicit Runtime(int threads = 0, int device = -1);
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;
  bool owns_kokkos() const { return owns_; }  // this object initialised Kokkos and finalises it

 private:
  bool owns_ = false;
};

// Human-readable lines about the devices and host threads this build can use.
std::vector<std::string> describe_devices();

// Bytes in use on the CUDA device (all processes), or -1 without CUDA.
long device_memory_used_bytes();

}  // namespace weft
