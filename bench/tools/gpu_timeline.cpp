// A Kokkos Tools library that times each kernel on the GPU without fencing it: a CUDA event is recorded on
// the default stream before and after every launch, and the events are read at exit. So the run keeps its
// pace (the host queues ahead as in a user's run), and the gaps between one kernel's end and the next one's
// start show how long the GPU sat idle waiting for the host: launch latency, read-backs of counts, host work.
//
//   KOKKOS_PROFILE_LIBRARY=build/cuda/lib/libweft_gpu_timeline.so   (Kokkos 3.x; KOKKOS_TOOLS_LIBS with 4.x)
//   WEFT_TIMELINE_OUT=timeline.txt   (optional; default: standard error)
//   WEFT_TIMELINE_FROM=weft::predict:11   (optional: record from the 11th launch of that kernel on, e.g. to
//                                          leave out the first frame)
//
// Kokkos Tools regions (weft's stages: weft::constraints, weft::collision_pass, weft::broad_phase, ...) get
// their GPU span from an event recorded at the region's start and one at its end: the time the stage held
// the GPU, its kernels, graphs and idle gaps included.
//
// Kernels inside a CUDA graph (the Gauss-Seidel sweeps) are not launches Kokkos reports: their run lands
// in the gap before the next reported kernel. Needs the CUDA driver (libcuda, looked up at run time); on
// other backends it reports nothing.
#include <dlfcn.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace {

using Event = void*;  // CUevent
struct Driver {
  int (*event_create)(Event*, unsigned) = nullptr;
  int (*event_record)(Event, void*) = nullptr;
  int (*elapsed)(float*, Event, Event) = nullptr;
  int (*sync)() = nullptr;
  bool ok() const { return event_create && event_record && elapsed && sync; }
};

struct Launch {
  int name;  // index into names
  Event start, end;
};

struct State {
  Driver cu;
  bool recording = false;
  std::string from_name;
  long from_count = 1, seen = 0;
  std::vector<std::string> names;
  std::map<std::string, int> name_index;
  std::vector<Launch> launches;
  std::vector<Launch> regions;     // closed regions, and open ones on `open`
  std::vector<size_t> open;
  std::vector<Event> pool;  // events created ahead, taken in order
  size_t next_event = 0;
};

State& state() {
  static State s;
  return s;
}

Event take_event() {
  State& s = state();
  if (s.next_event == s.pool.size()) {
    const size_t grow = s.pool.empty() ? 4096 : s.pool.size();
    for (size_t i = 0; i < grow; ++i) {
      Event e = nullptr;
      if (s.cu.event_create(&e, 0) != 0) return nullptr;
      s.pool.push_back(e);
    }
  }
  return s.pool[s.next_event++];
}

// The driver as the program loaded it, looked up at each launch until found: the CUDA runtime loads it
// only when Kokkos initializes its device, after this library and after the host's first kernels.
bool driver(State& s) {
  if (s.cu.ok()) return true;
  if (void* lib = dlopen("libcuda.so.1", RTLD_NOW | RTLD_NOLOAD)) {
    s.cu.event_create = reinterpret_cast<int (*)(Event*, unsigned)>(dlsym(lib, "cuEventCreate"));
    s.cu.event_record = reinterpret_cast<int (*)(Event, void*)>(dlsym(lib, "cuEventRecord"));
    s.cu.elapsed = reinterpret_cast<int (*)(float*, Event, Event)>(dlsym(lib, "cuEventElapsedTime"));
    s.cu.sync = reinterpret_cast<int (*)()>(dlsym(lib, "cuCtxSynchronize"));
  }
  return s.cu.ok();
}

uint64_t begin(const char* name) {
  State& s = state();
  if (!driver(s)) return ~0ull;
  if (!s.recording && (s.from_name.empty() || (s.from_name == name && ++s.seen >= s.from_count))) s.recording = true;
  if (!s.recording) return ~0ull;
  auto it = s.name_index.find(name);
  if (it == s.name_index.end()) {
    it = s.name_index.emplace(name, int(s.names.size())).first;
    s.names.push_back(name);
  }
  Launch l{it->second, take_event(), nullptr};
  if (!l.start) return ~0ull;
  s.cu.event_record(l.start, nullptr);
  s.launches.push_back(l);
  return s.launches.size() - 1;
}

void end(uint64_t id) {
  State& s = state();
  if (id == ~0ull) return;
  Launch& l = s.launches[id];
  l.end = take_event();
  if (l.end) s.cu.event_record(l.end, nullptr);
}

struct Total {
  long count = 0;
  double ms = 0;
};

void print_table(FILE* out, const char* title, std::map<std::string, Total>& by_name, double all) {
  std::vector<std::pair<std::string, Total>> rows(by_name.begin(), by_name.end());
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.second.ms > b.second.ms; });
  std::fprintf(out, "\n%s\n%12s %10s %10s %6s  %s\n", title, "total ms", "count", "mean us", "%", "name");
  for (const auto& [name, t] : rows)
    std::fprintf(out, "%12.2f %10ld %10.1f %6.1f  %s\n", t.ms, t.count, 1e3 * t.ms / t.count, 100 * t.ms / all,
                 name.c_str());
}

}  // namespace

extern "C" {

void kokkosp_init_library(int, uint64_t, uint32_t, void*) {
  State& s = state();
  if (const char* f = std::getenv("WEFT_TIMELINE_FROM")) {
    const char* colon = std::strrchr(f, ':');
    s.from_name = colon ? std::string(f, colon) : std::string(f);
    s.from_count = colon ? std::atol(colon + 1) : 1;
  }
}

void kokkosp_begin_parallel_for(const char* name, uint32_t, uint64_t* id) { *id = begin(name); }
void kokkosp_end_parallel_for(uint64_t id) { end(id); }
void kokkosp_begin_parallel_scan(const char* name, uint32_t, uint64_t* id) { *id = begin(name); }
void kokkosp_end_parallel_scan(uint64_t id) { end(id); }
void kokkosp_begin_parallel_reduce(const char* name, uint32_t, uint64_t* id) { *id = begin(name); }
void kokkosp_end_parallel_reduce(uint64_t id) { end(id); }

void kokkosp_push_profile_region(const char* name) {
  State& s = state();
  if (!s.cu.ok() || !s.recording) {
    s.open.push_back(~size_t(0));
    return;
  }
  auto it = s.name_index.find(name);
  if (it == s.name_index.end()) {
    it = s.name_index.emplace(name, int(s.names.size())).first;
    s.names.push_back(name);
  }
  Launch r{it->second, take_event(), nullptr};
  if (r.start) s.cu.event_record(r.start, nullptr);
  s.regions.push_back(r);
  s.open.push_back(s.regions.size() - 1);
}

void kokkosp_pop_profile_region() {
  State& s = state();
  if (s.open.empty()) return;
  const size_t id = s.open.back();
  s.open.pop_back();
  if (id == ~size_t(0)) return;
  Launch& r = s.regions[id];
  r.end = take_event();
  if (r.end) s.cu.event_record(r.end, nullptr);
}

void kokkosp_finalize_library() {
  State& s = state();
  FILE* out = stderr;
  if (const char* path = std::getenv("WEFT_TIMELINE_OUT"))
    if (FILE* f = std::fopen(path, "w")) out = f;
  if (!s.cu.ok() || s.launches.empty()) {
    std::fprintf(out, "gpu timeline: nothing recorded (CUDA driver %s, %ld launches of %s seen, %ld wanted)\n",
                 s.cu.ok() ? "found" : "not found", s.seen, s.from_name.empty() ? "the first kernel" : s.from_name.c_str(),
                 s.from_count);
    if (out != stderr) std::fclose(out);
    return;
  }
  s.cu.sync();
  std::map<std::string, Total> run, gap_before;
  double busy = 0, idle = 0;
  const Launch* prev = nullptr;
  for (const Launch& l : s.launches) {
    if (!l.end) continue;
    float ms = 0;
    s.cu.elapsed(&ms, l.start, l.end);
    Total& r = run[s.names[l.name]];
    r.count += 1;
    r.ms += ms;
    busy += ms;
    if (prev) {
      float g = 0;
      s.cu.elapsed(&g, prev->end, l.start);
      Total& t = gap_before[s.names[l.name]];
      t.count += 1;
      t.ms += g;
      idle += g;
    }
    prev = &l;
  }
  float whole = 0;
  if (prev) s.cu.elapsed(&whole, s.launches.front().start, prev->end);
  const double span = whole > 0 ? whole : 1e-9;
  std::fprintf(out, "gpu timeline: %zu launches over %.2f ms: kernels %.2f ms (%.1f%%), between kernels %.2f ms "
               "(%.1f%%: launch latency, read-backs, host work, and the CUDA graphs' runs)\n",
               s.launches.size(), span, busy, 100 * busy / span, idle, 100 * idle / span);
  std::map<std::string, Total> region;
  for (const Launch& r : s.regions) {
    if (!r.start || !r.end) continue;
    float ms = 0;
    s.cu.elapsed(&ms, r.start, r.end);
    Total& t = region[s.names[r.name]];
    t.count += 1;
    t.ms += ms;
  }
  if (!region.empty())
    print_table(out, "regions (weft's stages; GPU span from start to end, nested ones inside their parents)", region, span);
  print_table(out, "kernels (GPU time, unfenced)", run, span);
  print_table(out, "time between the previous kernel's end and this kernel's start", gap_before, span);
  if (out != stderr) std::fclose(out);
}

}  // extern "C"
