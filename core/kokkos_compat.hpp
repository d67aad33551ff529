// Every difference between Kokkos 3.4 and 4.x/5.x that weft touches lives here.
#pragma once
#include <Kokkos_Core.hpp>
#include <Kokkos_Graph.hpp>

#include <cstdlib>
#include <string>

namespace weft::compat {

inline constexpr int kokkos_version = KOKKOS_VERSION;  // e.g. 30401

inline std::string kokkos_version_string() {
  return std::to_string(KOKKOS_VERSION / 10000) + "." + std::to_string(KOKKOS_VERSION / 100 % 100) + "." +
         std::to_string(KOKKOS_VERSION % 100);
}

// Initialise Kokkos with a host thread count (<= 0: Kokkos' default) and a CUDA device (< 0: default).
inline void initialize(int num_threads, int device_id) {
  // Unset, the OpenMP runtime binds no threads, which is what weft wants; Kokkos 4 would print four lines
  // of advice on every run. Saying so explicitly keeps them away (a value the user set is kept).
  ::setenv("OMP_PROC_BIND", "false", 0);
#if KOKKOS_VERSION >= 40000
  Kokkos::InitializationSettings s;
  if (num_threads > 0) s.set_num_threads(num_threads);
  if (device_id >= 0) s.set_device_id(device_id);
  Kokkos::initialize(s);
#else
  Kokkos::InitArguments a;
  a.num_threads = num_threads > 0 ? num_threads : -1;
  a.device_id = device_id;
  a.disable_warnings = true;
  Kokkos::initialize(a);
#endif
}

// Number of threads of a host execution space.
template <class Exec>
int concurrency() {
#if KOKKOS_VERSION >= 40000
  return Exec().concurrency();
#else
  return Exec::concurrency();
#endif
}

// Kernel graphs (CUDA graphs on the device; the host backends run the nodes in order). Kokkos 3.4's
// CUDA implementation needs scripts/kokkos/*.patch under CUDA 12 and later.
template <class Exec>
using Graph = Kokkos::Experimental::Graph<Exec>;
template <class Exec>
using GraphNode = Kokkos::Experimental::GraphNodeRef<Exec>;
template <class Exec, class Closure>
Graph<Exec> create_graph(const Exec& exec, Closure&& c) {
  return Kokkos::Experimental::create_graph(exec, std::forward<Closure>(c));
}
// A node that follows both a and b (they may run at the same time).
template <class Exec>
GraphNode<Exec> when_all(const GraphNode<Exec>& a, const GraphNode<Exec>& b) {
  return Kokkos::Experimental::when_all(a, b);
}

}  // namespace weft::compat
