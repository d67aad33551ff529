// Colours contacts on the device so that no two contacts of one colour move the same cloth point
// (Jones-Plassmann): each round, every uncoloured contact whose priority key is the largest among the
// uncoloured contacts at each of its cloth points takes the round's colour. Keys are a hash of the contact
// index joined with the index (unique), and the per-point maximum is an integer atomic max: the result
// depends only on the contact list. Contacts are then sorted by colour (unique keys colour, index).
#pragma once
#include "collision/contact.hpp"
#include "core/hash.hpp"
#include "core/compact.hpp"
#include "core/device_copy.hpp"
#include "core/sort.hpp"

#include <Kokkos_Core.hpp>
#include <vector>

namespace weft {

namespace colouring_detail {

// Round (16 bits, from 1), hash (16 bits), index (32 bits): unique within a round, never 0.
KOKKOS_INLINE_FUNCTION uint64_t priority(long i, int round) {
  return uint64_t(round + 1) << 48 | (splitmix64(uint64_t(i)) & 0x0000FFFF00000000ull) | uint64_t(i);
}

// The round's kernels, as named functors (docs/solver.md, "Kernels are functors").
template <class Mem>
struct Start {
  Kokkos::View<int*, Mem> col;
  Kokkos::View<uint32_t*, Mem> todo;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    col(i) = -1;
    todo(i) = uint32_t(i);
  }
};

// Every uncoloured contact claims its moving points with its key (integer atomic max).
// A contact moves point k when k is a cloth point with nonzero weight b and inverse mass w: only such points
// can conflict (projection writes no other).
template <class Mem>
KOKKOS_INLINE_FUNCTION bool moves(const Contact& c, int k, const Kokkos::View<real*, Mem>& w) {
  return c.p[k] >= 0 && c.b[k] != 0 && w(c.p[k]) > 0;
}

template <class Mem>
struct Claim {
  Kokkos::View<Contact*, Mem> c;
  Kokkos::View<real*, Mem> w;
  Kokkos::View<uint32_t*, Mem> todo;
  Kokkos::View<uint64_t*, Mem> owner;
  Kokkos::View<int*, Mem> col;
  int round;
  KOKKOS_INLINE_FUNCTION void operator()(long t) const {
    const long i = todo(t);
    if (col(i) >= 0) return;  // coloured in an earlier round since the last compaction
    const uint64_t key = priority(i, round);
    for (int k = 0; k < 4; ++k)
      if (moves(c(i), k, w)) Kokkos::atomic_fetch_max(&owner(c(i).p[k]), key);
  }
};

// A contact that holds all its points takes the round's colour.
template <class Mem>
struct Take {
  Kokkos::View<Contact*, Mem> c;
  Kokkos::View<real*, Mem> w;
  Kokkos::View<uint32_t*, Mem> todo;
  Kokkos::View<uint64_t*, Mem> owner;
  Kokkos::View<int*, Mem> col;
  int round;
  KOKKOS_INLINE_FUNCTION void operator()(long t) const {
    const long i = todo(t);
    if (col(i) >= 0) return;
    const uint64_t key = priority(i, round);
    bool win = true;
    for (int k = 0; k < 4; ++k)
      if (moves(c(i), k, w)) win = win && owner(c(i).p[k]) == key;
    if (win) col(i) = round;
  }
};

// Compaction of the still uncoloured contacts (count and fill of count_scan_fill).
template <class Mem>
struct StillUncoloured {
  Kokkos::View<int*, Mem> col;
  Kokkos::View<uint32_t*, Mem> todo;
  KOKKOS_INLINE_FUNCTION long operator()(long t) const { return col(todo(t)) < 0 ? 1 : 0; }
};
template <class Mem>
struct KeepUncoloured {
  Kokkos::View<int*, Mem> col;
  Kokkos::View<uint32_t*, Mem> todo, out;
  KOKKOS_INLINE_FUNCTION void operator()(long t, long o) const {
    if (col(todo(t)) < 0) out(o) = todo(t);
  }
};

template <class Mem>
struct ColourKeys {
  Kokkos::View<int*, Mem> col;
  Kokkos::View<uint64_t*, Mem> keys;
  Kokkos::View<uint32_t*, Mem> order;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    keys(i) = uint64_t(col(i)) << 32 | uint64_t(i);
    order(i) = uint32_t(i);
  }
};

template <class Mem>
struct Gather {
  Kokkos::View<Contact*, Mem> c, sorted;
  Kokkos::View<uint32_t*, Mem> order;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { sorted(i) = c(order(i)); }
};

// first(colour) = index of its first contact in the sorted list; first(last + 1) = n.
template <class Mem>
struct ColourBounds {
  Kokkos::View<uint64_t*, Mem> keys;
  Kokkos::View<long*, Mem> first;
  long n;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const long ci = long(keys(i) >> 32);
    if (i == 0 || long(keys(i - 1) >> 32) != ci) first(ci) = i;
    if (i == n - 1) first(ci + 1) = n;
  }
};

}  // namespace colouring_detail

template <class Exec>
class ContactColouring {
 public:
  using Mem = typename Exec::memory_space;

  // Reorders contacts(0..n) by colour; returns the colour ranges [offsets[c], offsets[c+1]).
  // w: the cloth points' inverse masses (points that cannot move never conflict).
  std::vector<long> colour(const Exec& exec, Kokkos::View<Contact*, Mem>& contacts, long n,
                           const Kokkos::View<real*, Mem>& w) {
    const long points = long(w.extent(0));
    using namespace colouring_detail;
    std::vector<long> offsets{0};
    if (n == 0) return offsets;
    grow(owner_, points);
    grow(colour_, n);
    grow(keys_, n);
    grow(order_, n);
    grow(sorted_, n);
    grow(todo_, n);
    grow(spare_, n);
    grow(next_, n + 1);
    Kokkos::deep_copy(exec, owner_, 0ull);
    auto todo = todo_, spare = spare_;
    Kokkos::parallel_for("weft::jp_init", Kokkos::RangePolicy<Exec>(exec, 0, n), Start<Mem>{colour_, todo});
    // Keys carry the round in their top bits, so a point's stale claim from an earlier round always loses
    // and owners never need resetting. The uncoloured contacts are compacted (and their count read back,
    // a host-device sync) only every kRoundsPerSync rounds; contacts coloured in between sit the rest out.
    constexpr int kRoundsPerSync = 8;
    int rounds = 0;
    for (long left = n; left > 0;) {
      for (int k = 0; k < kRoundsPerSync; ++k, ++rounds) {
        Kokkos::parallel_for("weft::jp_claim", Kokkos::RangePolicy<Exec>(exec, 0, left),
                             Claim<Mem>{contacts, w, todo, owner_, colour_, rounds});
        Kokkos::parallel_for("weft::jp_take", Kokkos::RangePolicy<Exec>(exec, 0, left),
                             Take<Mem>{contacts, w, todo, owner_, colour_, rounds});
      }
      left = count_scan_fill(exec, left, next_, StillUncoloured<Mem>{colour_, todo},
                             KeepUncoloured<Mem>{colour_, todo, spare});
      std::swap(todo, spare);
    }
    // Sort by (colour, index) and count each colour.
    Kokkos::View<uint64_t*, Mem> kv = Kokkos::subview(keys_, std::make_pair(0L, n));
    Kokkos::View<uint32_t*, Mem> ov = Kokkos::subview(order_, std::make_pair(0L, n));
    Kokkos::parallel_for("weft::contact_keys", Kokkos::RangePolicy<Exec>(exec, 0, n), ColourKeys<Mem>{colour_, kv, ov});
    radix_sort_pairs(exec, kv, ov, 48);  // colour < 2^16 above a 32-bit index
    Kokkos::parallel_for("weft::contact_gather", Kokkos::RangePolicy<Exec>(exec, 0, n), Gather<Mem>{contacts, sorted_, ov});
    grow(first_, rounds + 1);
    Kokkos::parallel_for("weft::colour_bounds", Kokkos::RangePolicy<Exec>(exec, 0, n), ColourBounds<Mem>{kv, first_, n});
    const auto h = to_host(Kokkos::subview(first_, std::make_pair(0L, long(rounds + 1))));
    // Every round colours at least one contact until none is left (the largest key always wins), so the
    // colours are 0..k-1 with first(k) = n; the batch's last rounds may have found nothing to colour.
    int colours = 1;
    while (h[colours] != n) ++colours;
    offsets.assign(h.begin(), h.begin() + colours + 1);
    std::swap(contacts, sorted_);
    return offsets;
  }

 private:
  template <class V>
  static void grow(V& v, long n) {
    if (long(v.extent(0)) < n) v = V(Kokkos::view_alloc(Kokkos::WithoutInitializing, v.label()), n + n / 2 + 16);
  }
  Kokkos::View<uint64_t*, Mem> owner_{"weft::jp_owner", 0}, keys_{"weft::jp_keys", 0};
  Kokkos::View<int*, Mem> colour_{"weft::jp_colour", 0};
  Kokkos::View<uint32_t*, Mem> order_{"weft::jp_order", 0}, todo_{"weft::jp_todo", 0},
      spare_{"weft::jp_spare", 0};
  Kokkos::View<long*, Mem> next_{"weft::jp_next", 0}, first_{"weft::colour_first", 0};
  Kokkos::View<Contact*, Mem> sorted_{"weft::contacts_sorted", 0};
};

}  // namespace weft
