#include "surge/io/vtk_writer.hpp"

#include "surge/io/atomic_file.hpp"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace surge::io {
namespace {

// Appends one raw block (UInt64 byte count, then the bytes) and returns its offset.
template <class T>
std::size_t append_block(std::string& blob, const std::vector<T>& data) {
  const std::size_t offset = blob.size();
  const std::uint64_t nbytes = data.size() * sizeof(T);
  blob.append(reinterpret_cast<const char*>(&nbytes), sizeof nbytes);
  blob.append(reinterpret_cast<const char*>(data.data()), nbytes);
  return offset;
}

template <class T>
const char* vtk_type() {
  if constexpr (std::is_same_v<T, double>)
    return "Float64";
  else if constexpr (std::is_same_v<T, float>)
    return "Float32";
  else if constexpr (std::is_same_v<T, std::uint8_t>)
    return "UInt8";
  else if constexpr (std::is_same_v<T, std::uint32_t>)
    return "UInt32";
  else
    return "Int64";
}

} // namespace

namespace {
// Builds a PolyData file of points: points first, then point-data arrays.
class VtpBuilder {
public:
  // n points; lines: point-index pairs (a line cell each), for bond networks; triangles:
  // point-index triples (a polygon each), for wall surfaces.
  explicit VtpBuilder(std::size_t n, std::vector<std::int64_t> lines = {}, std::vector<std::int64_t> triangles = {})
      : lines_(std::move(lines)), tris_(std::move(triangles)) {
    x_ << "<?xml version=\"1.0\"?>\n"
       << "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
       << "<PolyData>\n<Piece NumberOfPoints=\"" << n << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << lines_.size() / 2
       << "\" NumberOfStrips=\"0\" NumberOfPolys=\"" << tris_.size() / 3 << "\">\n";
  }
  void points(const std::vector<double>& xyz) {
    x_ << "<Points>\n";
    array("position", xyz, 3);
    x_ << "</Points>\n<PointData Vectors=\"velocity\">\n";
  }
  template <class T>
  void array(const char* name, const std::vector<T>& data, int comps) {
    const std::size_t off = append_block(blob_, data);
    x_ << "<DataArray type=\"" << vtk_type<T>() << "\" Name=\"" << name << "\" NumberOfComponents=\"" << comps
       << "\" format=\"appended\" offset=\"" << off << "\"/>\n";
  }
  void write(const std::string& path) {
    x_ << "</PointData>\n";
    cells("Lines", lines_, 2);
    cells("Polys", tris_, 3);
    x_ << "</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_";
    std::string out = x_.str();
    out += blob_;
    out += "\n</AppendedData>\n</VTKFile>\n";
    write_file_atomic(path, out);
  }

private:
  // A cell section (Lines, Polys) of cells of `per` points each, if there are any.
  void cells(const char* tag, const std::vector<std::int64_t>& connectivity, std::size_t per) {
    if (connectivity.empty()) return;
    std::vector<std::int64_t> offsets;
    for (std::size_t k = per; k <= connectivity.size(); k += per) offsets.push_back(static_cast<std::int64_t>(k));
    x_ << "<" << tag << ">\n";
    array("connectivity", connectivity, 1);
    array("offsets", offsets, 1);
    x_ << "</" << tag << ">\n";
  }
  std::vector<std::int64_t> lines_, tris_;
  std::ostringstream x_;
  std::string blob_;
};

void push3(std::vector<float>& v, const Vec3& a) {
  v.insert(v.end(), {static_cast<float>(a.x), static_cast<float>(a.y), static_cast<float>(a.z)});
}
void push3(std::vector<double>& v, const Vec3d& a) { v.insert(v.end(), {a.x, a.y, a.z}); }
} // namespace

void write_particles_vtp(const std::string& path, const particles::HostParticles& h, const Vec3d& origin,
                         std::initializer_list<Kind> kinds) {
  std::vector<double> pos;
  std::vector<float> vel, rho, press;
  std::vector<std::uint8_t> kind, surface;
  std::vector<std::uint32_t> id;
  bool marked = h.surface.size() == h.size(); // the surface flags, for water
  for (Kind k : kinds) marked = marked && k == Kind::Fluid;
  for (std::size_t i = 0; i < h.size(); ++i) {
    bool take = false;
    for (Kind k : kinds) take = take || h.kind[i] == static_cast<std::uint8_t>(k);
    if (!take) continue;
    push3(pos, origin + Vec3d(h.pos[i]));
    push3(vel, h.vel[i]);
    rho.push_back(static_cast<float>(h.rho[i]));
    press.push_back(static_cast<float>(h.press[i]));
    kind.push_back(h.kind[i]);
    id.push_back(h.id[i]);
    if (marked) surface.push_back(h.surface[i]);
  }
  VtpBuilder b(id.size());
  b.points(pos);
  b.array("velocity", vel, 3);
  b.array("density", rho, 1);
  b.array("pressure", press, 1);
  b.array("kind", kind, 1);
  b.array("id", id, 1);
  if (marked) b.array("surface", surface, 1);
  b.write(path);
}

void write_image_vti(const std::string& path, long nx, long ny, double x0, double y0, double dx, double dy,
                     const std::vector<std::string>& names, const std::vector<std::vector<double>>& arrays) {
  std::ostringstream x;
  x.precision(17);
  x << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
    << "<ImageData WholeExtent=\"0 " << nx - 1 << " 0 " << ny - 1 << " 0 0\" Origin=\"" << x0 << " " << y0
    << " 0\" Spacing=\"" << dx << " " << dy << " 1\">\n<Piece Extent=\"0 " << nx - 1 << " 0 " << ny - 1
    << " 0 0\">\n<PointData>\n";
  std::string blob;
  for (std::size_t k = 0; k < arrays.size(); ++k) {
    const std::size_t off = append_block(blob, arrays[k]);
    x << "<DataArray type=\"Float64\" Name=\"" << names[k] << "\" format=\"appended\" offset=\"" << off << "\"/>\n";
  }
  x << "</PointData>\n</Piece>\n</ImageData>\n<AppendedData encoding=\"raw\">\n_";
  std::string out = x.str();
  out += blob;
  out += "\n</AppendedData>\n</VTKFile>\n";
  write_file_atomic(path, out);
}

void write_spheres_vtp(const std::string& path, const SphereFrame& s, const Vec3d& origin) {
  std::vector<double> pos;
  std::vector<float> vel, omega, radius;
  for (std::size_t i = 0; i < s.pos.size(); ++i) {
    push3(pos, origin + Vec3d(s.pos[i]));
    push3(vel, s.vel[i]);
    push3(omega, s.omega[i]);
    radius.push_back(static_cast<float>(s.radius[i]));
  }
  std::vector<std::int64_t> lines(s.bonds.begin(), s.bonds.end());
  VtpBuilder b(s.pos.size(), std::move(lines));
  b.points(pos);
  b.array("velocity", vel, 3);
  b.array("angular_velocity", omega, 3);
  b.array("radius", radius, 1);
  b.array("material", s.material, 1);
  b.array("contacts", s.contacts, 1);
  b.array("id", s.id, 1);
  b.write(path);
}

void write_triangles_vtp(const std::string& path, const std::vector<std::array<Vec3, 3>>& tris, const Vec3d& origin) {
  std::vector<double> pos;
  std::vector<std::int64_t> cells;
  for (const auto& t : tris)
    for (const Vec3& p : t) {
      cells.push_back(static_cast<std::int64_t>(cells.size()));
      push3(pos, origin + Vec3d(p));
    }
  const std::size_t n = cells.size(); // (before cells is moved into the builder)
  VtpBuilder b(n, {}, std::move(cells));
  b.points(pos);
  b.write(path);
}

void PvdCollection::add(double time, const std::string& relative_file) {
  entries_.emplace_back(time, relative_file);
  std::ostringstream x;
  x.precision(10);
  x << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
       "byte_order=\"LittleEndian\">\n<Collection>\n";
  for (const auto& [t, f] : entries_) x << "<DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << f << "\"/>\n";
  x << "</Collection>\n</VTKFile>\n";
  write_file_atomic(path_, x.str());
}

FrameSeries::FrameSeries(const std::string& out_dir, const std::string& stem)
    : out_dir_(out_dir), stem_(stem), pvd_(out_dir + "/" + stem + ".pvd") {}

std::string FrameSeries::relative(int frame) const {
  char num[16];
  std::snprintf(num, sizeof num, "_%04d.vtp", frame);
  return "particles/" + stem_ + num;
}

void FrameSeries::restored(const std::vector<double>& times) {
  std::vector<std::pair<double, std::string>> entries;
  for (std::size_t k = 0; k < times.size(); ++k) entries.emplace_back(times[k], relative(static_cast<int>(k)));
  pvd_.restore(entries);
}

} // namespace surge::io
