// Copies between host vectors and device Views, the one place they are written. Every copy is synchronous
// (Kokkos::deep_copy without an execution space instance): the host side may be a temporary.
#pragma once
#include <Kokkos_Core.hpp>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace weft {

// h into d, which has h.size() elements and is contiguous (a View or a range of one).
template <class T, class... P>
void copy_to_device(const Kokkos::View<T*, P...>& d, const std::vector<T>& h) {
  Kokkos::deep_copy(d, Kokkos::View<const T*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>(h.data(), h.size()));
}

// A new View in Mem holding h.
template <class Mem, class T>
Kokkos::View<T*, Mem> upload(const std::vector<T>& h, const std::string& label) {
  Kokkos::View<T*, Mem> d(Kokkos::view_alloc(Kokkos::WithoutInitializing, label), h.size());
  copy_to_device(d, h);
  return d;
}

// A table of rows of N (triangles' corners, say), through a mirror: the device layout may be column-major.
template <class Mem, class T, size_t N>
Kokkos::View<T* [N], Mem> upload_table(const std::vector<std::array<T, N>>& h, const std::string& label) {
  Kokkos::View<T* [N], Mem> d(label, h.size());
  auto m = Kokkos::create_mirror_view(d);
  for (size_t i = 0; i < h.size(); ++i)
    for (size_t k = 0; k < N; ++k) m(i, k) = h[i][k];
  Kokkos::deep_copy(d, m);
  return d;
}

// Frames x points (an animation): every frame as long as the first; none gives an empty View.
template <class Mem, class T>
Kokkos::View<T**, Mem> upload_frames(const std::vector<std::vector<T>>& frames, const std::string& label) {
  const size_t nf = frames.size(), n = nf ? frames[0].size() : 0;
  Kokkos::View<T**, Mem> d(label, nf, n);
  auto m = Kokkos::create_mirror_view(d);
  for (size_t f = 0; f < nf; ++f)
    for (size_t i = 0; i < n; ++i) m(f, i) = frames[f][i];
  Kokkos::deep_copy(d, m);
  return d;
}

// A rank-1 View's elements on the host.
template <class V>
std::vector<typename V::non_const_value_type> to_host(const V& d) {
  const auto m = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), d);
  std::vector<typename V::non_const_value_type> out(m.extent(0));
  for (size_t i = 0; i < out.size(); ++i) out[i] = m(i);
  return out;
}

}  // namespace weft
