// VTK XML PolyData (.vtp) with raw binary appended data, and .pvd time collections.
#pragma once
#include "surge/core/types.hpp"
#include "surge/particles/particle_store.hpp"
#include <array>

#include <string>
#include <vector>

namespace surge::io {

// Writes the particles whose kind is in `kinds` to a .vtp; positions are written
// in double as origin + local position.
void write_particles_vtp(const std::string& path, const particles::HostParticles& h, const Vec3d& origin,
                         std::initializer_list<Kind> kinds);

// DEM spheres of one output time, by id (positions local, like particles).
struct SphereFrame {
  std::vector<Vec3> pos, vel, omega;
  std::vector<Real> radius;
  std::vector<std::uint8_t> material;
  std::vector<std::uint32_t> contacts, id;
  std::vector<std::uint32_t> bonds; // intact bonds as pairs of sphere indices (written as line cells)
};
// Sphere centres with velocity, angular_velocity, radius, material, contacts, id, and
// the intact bonds as lines.
void write_spheres_vtp(const std::string& path, const SphereFrame& s, const Vec3d& origin);
// Triangles (local coordinates; each its own three points) as polygons: the DEM's moving
// walls in each frame.
void write_triangles_vtp(const std::string& path, const std::vector<std::array<Vec3, 3>>& tris, const Vec3d& origin);

// A horizontal grid of nx x ny nodes (x0 + i dx, y0 + j dy, z = 0), node j * nx + i, as VTK
// ImageData (.vti) with one Float64 point array per name (NaN where a value is missing).
void write_image_vti(const std::string& path, long nx, long ny, double x0, double y0, double dx, double dy,
                     const std::vector<std::string>& names, const std::vector<std::vector<double>>& arrays);

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

// One series of frames of a run: files particles/<stem>_NNNN.vtp under the output folder
// and their collection <stem>.pvd (fluid, walls, spheres, dem_walls).
class FrameSeries {
public:
  FrameSeries(const std::string& out_dir, const std::string& stem);
  // Where frame k's file goes (its writer writes it, then calls add).
  [[nodiscard]] std::string path(int frame) const { return out_dir_ + "/" + relative(frame); }
  void add(int frame, double t) { pvd_.add(t, relative(frame)); }
  // A restart: frames 0, 1, ... written at these times already.
  void restored(const std::vector<double>& times);

private:
  [[nodiscard]] std::string relative(int frame) const;
  std::string out_dir_, stem_;
  PvdCollection pvd_;
};

} // namespace surge::io
