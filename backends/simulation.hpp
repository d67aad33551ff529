// A simulation on the backend chosen at run time. backends/<backend>.cpp instantiate the solver for
// their execution space; the rest of weft sees only this interface.
#pragma once
#include "backends/backend.hpp"
#include "scene/scene.hpp"
#include "solver/frame_stats.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace weft {

class Simulation {
 public:
  virtual ~Simulation() = default;
  virtual FrameStats step_frame() = 0;            // frame() -> frame() + 1
  virtual FrameStats measure() const = 0;         // statistics of the current state
  virtual int frame() const = 0;
  virtual uint64_t hash_positions() const = 0;    // bitwise hash of the current positions
  virtual std::vector<Vec3> positions() const = 0;
  virtual std::vector<Vec3> velocities() const = 0;
  // Continue from a saved state (positions and velocities at `frame`): --resume gives the same bits as an
  // uninterrupted run, since nothing else carries over from one frame to the next.
  virtual void set_state(int frame, const std::vector<Vec3>& x, const std::vector<Vec3>& v) = 0;
  // Colliders streamed frame by frame (docs/library.md, "Streamed colliders"): the positions of every collider
  // vertex, concatenated in the scene's collider order, at the end of the frame the next step_frame() steps,
  // which moves the colliders linearly to them over its substeps. From the first call on the scene's collider
  // animation is not used (set_state goes back to it); a frame stepped without a new call keeps the colliders
  // where they are. Throws InputError for a wrong vertex count.
  virtual void set_collider_frame(const std::vector<Vec3>& x) = 0;
  // The same for the scene's collider `collider` alone; the others stay where their last frame put them.
  virtual void set_collider_frame(int collider, const std::vector<Vec3>& x) = 0;
  virtual int colour_count() const = 0;
  virtual long row_count() const = 0;
  virtual long tether_count() const = 0;
  // The q-quantile (0..1) of the triangles' strain (docs/solver.md, "Strain"; of the distance constraints'
  // |length / rest - 1| in a scene without triangles; 0 without either).
  virtual real strain_quantile(double q) const = 0;
  // Pairs of cloth triangles that intersect at the current positions (discrete check, adjacent pairs excluded).
  virtual long intersections() const = 0;
};

// Throws InputError for an invalid scene, std::runtime_error when `b` is not compiled in.
std::unique_ptr<Simulation> make_simulation(Backend b, const Scene& scene);

}  // namespace weft
