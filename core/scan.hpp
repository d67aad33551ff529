// Exclusive scans of integers (exact, so any order of the sums gives the same result). Blocks of kScanBlock
// values: each block's sum, the sums scanned the same way (one thread once they fit in a block), then each
// block's values from its offset, every block one thread that loads kScanAhead values before it uses them.
// Kokkos' parallel_scan took about 30 us a call on an H200 whatever the size below a few million, and the
// proximity passes scan some 150 times a frame; three short launches take a third of that.
#pragma once
#include <Kokkos_Core.hpp>

namespace weft {

inline constexpr long kScanBlock = 128;
inline constexpr int kScanAhead = 8;

namespace scan_detail {

// The working memory of the scans' block sums, kept between calls (as the reductions' is).
template <class T, class Mem>
Kokkos::View<T*, Mem> workspace(long n) {
  static Kokkos::View<T*, Mem>* ws = nullptr;
  if (!ws) {
    ws = new Kokkos::View<T*, Mem>();
    Kokkos::push_finalize_hook([] {
      delete ws;
      ws = nullptr;
    });
  }
  if (long(ws->extent(0)) < n)
    *ws = Kokkos::View<T*, Mem>(Kokkos::view_alloc(Kokkos::WithoutInitializing, "weft::scan_workspace"), n + n / 2 + 64);
  return *ws;
}

// Block sums, the sums' offsets and the total: elements for a scan of n values.
inline long levels_size(long n) {
  long total = 1;
  while (n > kScanBlock) {
    n = (n + kScanBlock - 1) / kScanBlock;
    total += n;
  }
  return total;
}

template <class In, class T, class Mem>
struct BlockSums {
  In in;
  Kokkos::View<T*, Mem> sums;
  long n;
  KOKKOS_INLINE_FUNCTION void operator()(long b) const {
    const long lo = b * kScanBlock, hi = lo + kScanBlock < n ? lo + kScanBlock : n;
    T acc = 0;
    long i = lo;
    for (; i + kScanAhead <= hi; i += kScanAhead) {
      T v[kScanAhead];
      for (int k = 0; k < kScanAhead; ++k) v[k] = in(i + k);
      for (int k = 0; k < kScanAhead; ++k) acc += v[k];
    }
    for (; i < hi; ++i) acc += in(i);
    sums(b) = acc;
  }
};

// out[lo, hi) from offset `start`; in may be out.
template <class In, class Out, class T>
KOKKOS_INLINE_FUNCTION T scan_range(const In& in, const Out& out, long lo, long hi, T acc) {
  long i = lo;
  for (; i + kScanAhead <= hi; i += kScanAhead) {
    T v[kScanAhead];
    for (int k = 0; k < kScanAhead; ++k) v[k] = in(i + k);
    for (int k = 0; k < kScanAhead; ++k) {
      out(i + k) = acc;
      acc += v[k];
    }
  }
  for (; i < hi; ++i) {
    const T v = in(i);
    out(i) = acc;
    acc += v;
  }
  return acc;
}

// All of a short list by one thread; its total into total().
template <class In, class Out, class T, class Mem>
struct ScanOne {
  In in;
  Out out;
  Kokkos::View<T*, Mem> total;  // one element
  long n;
  KOKKOS_INLINE_FUNCTION void operator()(long) const { total(0) = scan_range(in, out, 0, n, T(0)); }
};

// Block b's values from its offset.
template <class In, class Out, class T, class Mem>
struct ScanBlocks {
  In in;
  Out out;
  Kokkos::View<T*, Mem> offsets;
  long n;
  KOKKOS_INLINE_FUNCTION void operator()(long b) const {
    const long lo = b * kScanBlock, hi = lo + kScanBlock < n ? lo + kScanBlock : n;
    scan_range(in, out, lo, hi, offsets(b));
  }
};

// Scans in[0, n) into out, the total into ws(at) once the list fits one block.
template <class Exec, class In, class Out, class T>
void scan_levels(const Exec& exec, const In& in, const Out& out, long n,
                 const Kokkos::View<T*, typename Exec::memory_space>& ws, long at) {
  using Mem = typename Exec::memory_space;
  if (n <= kScanBlock) {
    Kokkos::parallel_for("weft::exclusive_scan", Kokkos::RangePolicy<Exec>(exec, 0, 1),
                         ScanOne<In, Out, T, Mem>{in, out, Kokkos::subview(ws, std::make_pair(at, at + 1)), n});
    return;
  }
  const long nb = (n + kScanBlock - 1) / kScanBlock;
  const Kokkos::View<T*, Mem> sums = Kokkos::subview(ws, std::make_pair(at, at + nb));
  Kokkos::parallel_for("weft::scan_block_sums", Kokkos::RangePolicy<Exec>(exec, 0, nb), BlockSums<In, T, Mem>{in, sums, n});
  scan_levels(exec, sums, sums, nb, ws, at + nb);
  Kokkos::parallel_for("weft::scan_blocks", Kokkos::RangePolicy<Exec>(exec, 0, nb),
                       ScanBlocks<In, Out, T, Mem>{in, out, sums, n});
}

// The scan on the device; returns where in the workspace its total lies.
template <class Exec, class InView, class OutView>
Kokkos::View<typename OutView::non_const_value_type*, typename Exec::memory_space> scan(const Exec& exec,
                                                                                      const InView& in,
                                                                                      const OutView& out) {
  using T = typename OutView::non_const_value_type;
  using Mem = typename Exec::memory_space;
  const long n = static_cast<long>(in.extent(0));
  const long size = levels_size(n);
  const Kokkos::View<T*, Mem> ws = workspace<T, Mem>(size);
  scan_levels(exec, in, out, n, ws, 0L);
  return Kokkos::subview(ws, std::make_pair(size - 1, size));
}

}  // namespace scan_detail

// out[i] = sum of in[0..i); returns the total (read back). in and out may be the same View.
template <class Exec, class InView, class OutView>
typename OutView::non_const_value_type exclusive_scan(const Exec& exec, const InView& in, const OutView& out) {
  using T = typename OutView::non_const_value_type;
  const auto total = scan_detail::scan(exec, in, out);
  T h = 0;
  Kokkos::deep_copy(exec, h, Kokkos::subview(total, 0));
  exec.fence();
  return h;
}

// out[i] = sum of in[0..i), without reading the total back: for callers that know it already.
template <class Exec, class InView, class OutView>
void exclusive_scan_on_device(const Exec& exec, const InView& in, const OutView& out) {
  scan_detail::scan(exec, in, out);
}

}  // namespace weft
