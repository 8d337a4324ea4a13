#include "surge/io/vtk_writer.hpp"

#include "surge/io/atomic_file.hpp"

#include <cstdint>
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

void write_particles_vtp(const std::string& path, const particles::HostParticles& h, const Vec3d& origin,
                         std::initializer_list<Kind> kinds) {
  std::vector<double> pos;
  std::vector<float> vel, rho, press;
  std::vector<std::uint8_t> kind;
  std::vector<std::uint32_t> id;
  for (std::size_t i = 0; i < h.size(); ++i) {
    bool take = false;
    for (Kind k : kinds) take = take || h.kind[i] == static_cast<std::uint8_t>(k);
    if (!take) continue;
    const Vec3d p = origin + Vec3d(h.pos[i]);
    pos.insert(pos.end(), {p.x, p.y, p.z});
    vel.insert(vel.end(),
               {static_cast<float>(h.vel[i].x), static_cast<float>(h.vel[i].y), static_cast<float>(h.vel[i].z)});
    rho.push_back(static_cast<float>(h.rho[i]));
    press.push_back(static_cast<float>(h.press[i]));
    kind.push_back(h.kind[i]);
    id.push_back(h.id[i]);
  }
  const std::size_t n = id.size();
  std::string blob;
  std::ostringstream x;
  x << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
    << "<PolyData>\n<Piece NumberOfPoints=\"" << n
    << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
  auto array = [&](const char* name, const auto& data, int comps) {
    using T = typename std::decay_t<decltype(data)>::value_type;
    const std::size_t off = append_block(blob, data);
    x << "<DataArray type=\"" << vtk_type<T>() << "\" Name=\"" << name << "\" NumberOfComponents=\"" << comps
      << "\" format=\"appended\" offset=\"" << off << "\"/>\n";
  };
  x << "<Points>\n";
  array("position", pos, 3);
  x << "</Points>\n<PointData Scalars=\"density\" Vectors=\"velocity\">\n";
  array("velocity", vel, 3);
  array("density", rho, 1);
  array("pressure", press, 1);
  array("kind", kind, 1);
  array("id", id, 1);
  x << "</PointData>\n</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_";
  std::string out = x.str();
  out += blob;
  out += "\n</AppendedData>\n</VTKFile>\n";
  write_file_atomic(path, out);
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

} // namespace surge::io
