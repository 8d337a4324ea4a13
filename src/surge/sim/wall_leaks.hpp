// Fluid found inside walls: counted at every output from the geometry of the case's walls
// (independently of the boundary model), reported in the progress output and summary.json.
#pragma once
#include "surge/core/case.hpp"
#include "surge/geometry/stl_mesh.hpp"
#include "surge/motion/pose.hpp"
#include "surge/particles/particle_store.hpp"

#include <memory>
#include <string>
#include <vector>

namespace surge::sim {

struct LeakCount {
  long count = 0;
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300}; // where (absolute)
  std::string wall;                                          // the first wall holding one
};

class WallLeaks {
public:
  explicit WallLeaks(const Case& c);
  // Fluid particles of `host` (positions relative to `origin`) behind a wall face.
  [[nodiscard]] LeakCount count(const particles::HostParticles& host, const Vec3d& origin) const;
  // Wall w has moved by `pose` about `pivot` (absolute, as placed): it is tested where it
  // is now (each point taken back to where the wall was placed).
  void set_pose(std::size_t w, const Vec3d& pivot, const motion::Pose& pose) {
    moved_.resize(walls_.size());
    moved_[w] = {true, pivot, pose};
  }

private:
  struct Moved {
    bool moved = false;
    Vec3d pivot{};
    motion::Pose pose;
  };
  std::vector<Moved> moved_;
  std::vector<WallSpec> walls_;
  std::vector<std::unique_ptr<geometry::Mesh>> meshes_;
  std::vector<Box> reach_; // each wall's bounding box with its layers: only fluid there is tested
  double band_ = 0;
};

// The run's record: the most fluid particles found in walls at one output, and when and
// where they were first found.
struct LeakRecord {
  long max_count = 0;
  double first_time = -1, max_time = -1;
  LeakCount first;
  void add(const LeakCount& n, double t);
  [[nodiscard]] std::string json() const;
};

} // namespace surge::sim
