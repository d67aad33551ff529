// Graph colouring of constraint rows: no two rows of one colour move the same particle, so a colour is
// projected in parallel without races. Greedy in row order, smallest free colour: the result depends only
// on the input. Particles that never move (inverse mass 0) may be shared within a colour.
#pragma once
#include <vector>

namespace weft {

struct Colouring {
  std::vector<int> colour;  // per row
  int count = 0;            // number of colours
};

// particles_of(r, out) writes the particles of row r into out (cleared by the caller) and returns how many.
template <class ParticlesOf>
Colouring colour_greedy(long rows, long particles, const std::vector<char>& movable, ParticlesOf particles_of) {
  Colouring c;
  c.colour.assign(rows, 0);
  std::vector<std::vector<unsigned long long>> used(particles);  // colour bitset per particle
  int idx[8];
  for (long r = 0; r < rows; ++r) {
    const int n = particles_of(r, idx);
    int col = 0;
    for (;; ++col) {
      bool free = true;
      for (int k = 0; k < n && free; ++k) {
        if (!movable[idx[k]]) continue;
        const auto& u = used[idx[k]];
        const size_t word = size_t(col) / 64;
        free = !(word < u.size() && (u[word] >> (col % 64) & 1ull));
      }
      if (free) break;
    }
    for (int k = 0; k < n; ++k) {
      if (!movable[idx[k]]) continue;
      auto& u = used[idx[k]];
      const size_t word = size_t(col) / 64;
      if (u.size() <= word) u.resize(word + 1, 0ull);
      u[word] |= 1ull << (col % 64);
    }
    c.colour[r] = col;
    if (col + 1 > c.count) c.count = col + 1;
  }
  return c;
}

}  // namespace weft
