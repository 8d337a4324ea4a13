// VTK XML PolyData (.vtp) with raw binary appended data, and .pvd time collections.
#pragma once
#include "surge/core/types.hpp"
#include "surge/particles/particle_store.hpp"

#include <string>
#include <vector>

namespace surge::io {

// Writes the particles whose kind is in `kinds` to a .vtp; positions are written
// in double as origin + local position.
void write_particles_vtp(const std::string& path, const particles::HostParticles& h, const Vec3d& origin,
                         std::initializer_list<Kind> kinds);

// A ParaView collection (fluid.pvd): rewritten atomically after each new file.
class PvdCollection {
public:
  explicit PvdCollection(std::string path) : path_(std::move(path)) {}
  void add(double time, const std::string& relative_file);
  // Entries already on disk (a restarted run), without rewriting the file.
  void restore(std::vector<std::pair<double, std::string>> entries) { entries_ = std::move(entries); }

private:
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

} // namespace surge::io
