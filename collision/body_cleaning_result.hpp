// What the animation solvability check (paper sec. 3, "Data cleaning"; docs/solvability.md) is asked to
// do and what it reports, host side and backend-free: the kernels are in collision/body_cleaning.hpp.
#pragma once
#include "scene/scene.hpp"

#include <string>
#include <vector>

namespace weft {

struct CleaningSettings {
  real reach = 0.05;          // m: cloth farther than this along a body normal does not lie on the body
  real step = 0.0005;         // m: how far interior points move per self-intersection step
  int max_steps = 400;        // self-intersection steps per frame
  int max_iterations = 200;   // gap-resolution (Jacobi) iterations per frame
  real overshoot = 0.01;      // resolve a gap to (1 + overshoot) x the reserved gap, so it ends clear of it
};

// One body frame (all colliders at frame_start + frame).
struct FrameCleaning {
  int frame = 0;                   // scene frame number
  long intersections_before = 0;   // intersecting body triangle pairs
  long interior_before = 0;        // body points inside the body (ray parity, closed colliders)
  long gap_violations_before = 0;  // body points closer than their reserved gap to the body (after step 2)
  int self_steps = 0;              // self-intersection steps taken
  int gap_iterations = 0;          // gap-resolution iterations taken
  long points_moved = 0;           // body points whose position changed
  real max_displacement = 0;       // m
  long intersections_left = 0, interior_left = 0, gap_violations_left = 0;
  bool clean() const { return intersections_left == 0 && interior_left == 0 && gap_violations_left == 0; }
};

struct BodyCleaning {
  std::vector<Collider> colliders;    // the cleaned body; a collider that did not move is copied bit for bit
  std::vector<real> reserved;         // per body vertex (colliders concatenated): summed layer thickness, m
  std::vector<FrameCleaning> frames;
  long reserved_points = 0;           // body vertices with at least one layer on them
  real max_reserved = 0;              // m
  bool clean() const {
    for (const FrameCleaning& f : frames)
      if (!f.clean()) return false;
    return true;
  }
  long points_moved() const {
    long n = 0;
    for (const FrameCleaning& f : frames) n += f.points_moved;
    return n;
  }
  long violations_left() const {
    long n = 0;
    for (const FrameCleaning& f : frames) n += f.intersections_left + f.interior_left + f.gap_violations_left;
    return n;
  }
  real max_displacement() const {
    real m = 0;
    for (const FrameCleaning& f : frames) m = f.max_displacement > m ? f.max_displacement : m;
    return m;
  }
};

// One line: frames, points moved, largest displacement, violations left, clean or not. With
// `cloth_pairs` > 0 (the cloth's triangle pairs that intersect at its start), those too, and not clean.
std::string cleaning_summary(const BodyCleaning& c, long cloth_pairs = 0);

}  // namespace weft
