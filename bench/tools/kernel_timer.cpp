// A Kokkos Tools library that times every kernel by name and tracks memory per space and label: where the
// frame's time and memory go, on any backend, without a profiler.
//
//   KOKKOS_PROFILE_LIBRARY=build/cuda/lib/libweft_kernel_timer.so   (Kokkos 3.x)
//   KOKKOS_TOOLS_LIBS=...                                          (Kokkos 4.x and later)
//   WEFT_KERNEL_TIMER_OUT=timer.txt   (optional; default: standard error)
//
// Each kernel is bracketed by a device synchronisation (cuCtxSynchronize, looked up at run time, so the
// library needs no CUDA to build), so its time is launch plus run, and the run is slower than without the
// tool. Kernels inside a CUDA graph (the Gauss-Seidel sweep) do not report. With the CUDA build on the H200
// no allocation event arrived (host builds report them); the cause is not found. At exit it writes the kernels
// sorted by total time, then for each memory space the live bytes per allocation label when its total
// peaked.
#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

struct Kernel {
  long calls = 0;
  double seconds = 0;
};

// One memory space: live bytes per label, and the labels' bytes when the total peaked.
struct Memory {
  std::map<std::string, long long> live;
  std::map<const void*, std::pair<std::string, uint64_t>> blocks;
  long long total = 0, peak = 0;
  std::map<std::string, long long> at_peak;
};

struct State {
  int (*sync)() = nullptr;  // cuCtxSynchronize, when the driver is loaded
  std::unordered_map<std::string, Kernel> kernels;
  std::vector<std::pair<std::string, Clock::time_point>> open;  // kernels begun, by id
  std::map<std::string, Memory> spaces;  // by memory space name
};

State& state() {
  static State s;
  return s;
}

void sync() {
  if (state().sync) state().sync();
}

uint64_t begin(const char* name) {
  sync();
  State& s = state();
  s.open.emplace_back(name, Clock::now());
  return s.open.size() - 1;
}

void end(uint64_t id) {
  sync();
  State& s = state();
  auto& [name, t0] = s.open[id];
  Kernel& k = s.kernels[name];
  k.calls += 1;
  k.seconds += std::chrono::duration<double>(Clock::now() - t0).count();
  if (id + 1 == s.open.size()) s.open.pop_back();
}

struct SpaceHandle {
  char name[64];
};


}  // namespace

extern "C" {

void kokkosp_init_library(int, uint64_t, uint32_t, void*) {
  if (void* lib = dlopen("libcuda.so.1", RTLD_NOW | RTLD_NOLOAD))
    state().sync = reinterpret_cast<int (*)()>(dlsym(lib, "cuCtxSynchronize"));
}

void kokkosp_begin_parallel_for(const char* name, uint32_t, uint64_t* id) { *id = begin(name); }
void kokkosp_end_parallel_for(uint64_t id) { end(id); }
void kokkosp_begin_parallel_scan(const char* name, uint32_t, uint64_t* id) { *id = begin(name); }
void kokkosp_end_parallel_scan(uint64_t id) { end(id); }
void kokkosp_begin_parallel_reduce(const char* name, uint32_t, uint64_t* id) { *id = begin(name); }
void kokkosp_end_parallel_reduce(uint64_t id) { end(id); }

void kokkosp_allocate_data(SpaceHandle space, const char* label, const void* ptr, uint64_t size) {
  Memory& s = state().spaces[space.name];
  s.blocks[ptr] = {label, size};
  s.live[label] += size;
  s.total += size;
  if (s.total > s.peak) {
    s.peak = s.total;
    s.at_peak = s.live;
  }
}

void kokkosp_deallocate_data(SpaceHandle space, const char*, const void* ptr, uint64_t) {
  Memory& s = state().spaces[space.name];
  auto it = s.blocks.find(ptr);
  if (it == s.blocks.end()) return;
  s.live[it->second.first] -= it->second.second;
  s.total -= it->second.second;
  s.blocks.erase(it);
}

void kokkosp_finalize_library() {
  State& s = state();
  FILE* out = stderr;
  if (const char* path = std::getenv("WEFT_KERNEL_TIMER_OUT"))
    if (FILE* f = std::fopen(path, "w")) out = f;
  std::vector<std::pair<std::string, Kernel>> k(s.kernels.begin(), s.kernels.end());
  std::sort(k.begin(), k.end(), [](const auto& a, const auto& b) { return a.second.seconds > b.second.seconds; });
  double all = 0;
  for (const auto& e : k) all += e.second.seconds;
  std::fprintf(out, "kernels (fenced launch + run), %.1f ms in all\n%12s %10s %10s %6s  %s\n", all * 1e3, "total ms",
               "calls", "mean us", "%", "name");
  for (const auto& [name, e] : k)
    std::fprintf(out, "%12.2f %10ld %10.1f %6.1f  %s\n", e.seconds * 1e3, e.calls, e.seconds / e.calls * 1e6,
                 100 * e.seconds / all, name.c_str());
  for (const auto& [space, mem] : s.spaces) {
    std::vector<std::pair<std::string, long long>> m(mem.at_peak.begin(), mem.at_peak.end());
    std::sort(m.begin(), m.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    std::fprintf(out, "\n%s memory at its peak, %.1f MiB in all (Kokkos allocations only)\n", space.c_str(),
                 mem.peak / 1048576.0);
    for (const auto& [label, bytes] : m)
      if (bytes >= 1024) std::fprintf(out, "%12.3f MiB  %s\n", bytes / 1048576.0, label.c_str());
  }
  if (out != stderr) std::fclose(out);
}

}  // extern "C"
