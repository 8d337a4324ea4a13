#include "surge/io/checkpoint.hpp"

#include "surge/core/error.hpp"
#include "surge/io/atomic_file.hpp"

#include <cstring>
#include <fstream>
#include <sstream>
#include <type_traits>

namespace surge::io {
namespace {

// The last byte is the version: 2 with the DEM state, 3 hazard maps, 4 free bodies, 5 the
// SPS stress (4 and 5 written only with what they add).
constexpr char magic[8] = {'S', 'U', 'R', 'G', 'E', 'C', 'K', '3'};

class Writer {
public:
  template <class T>
  void put(const T& v) {
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void put_vec(const std::vector<T>& v) {
    put<std::uint64_t>(v.size());
    bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  std::string bytes_;
};

class Reader {
public:
  Reader(const std::string& bytes, const std::string& path) : b_(bytes), path_(path) {}
  template <class T>
  T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, b_.data() + pos_, sizeof v);
    pos_ += sizeof v;
    return v;
  }
  template <class T>
  std::vector<T> get_vec() {
    const auto n = get<std::uint64_t>();
    if (n > b_.size()) fail();
    need(n * sizeof(T));
    std::vector<T> v(n);
    std::memcpy(v.data(), b_.data() + pos_, n * sizeof(T));
    pos_ += n * sizeof(T);
    return v;
  }
  [[noreturn]] void fail() const { throw InputError(path_, 0, "", "checkpoint is truncated or corrupt"); }
  void need(std::size_t n) const {
    if (pos_ + n > b_.size()) fail();
  }
  [[nodiscard]] bool done() const { return pos_ == b_.size(); }

private:
  const std::string& b_;
  std::string path_;
  std::size_t pos_ = 0;
};

} // namespace

void write_checkpoint(const std::string& path, const Checkpoint& c) {
  Writer w;
  w.bytes_.append(magic, sizeof magic);
  w.put<std::uint32_t>(sizeof(Real));
  w.put(c.time);
  w.put<std::int64_t>(c.steps);
  w.put<std::int32_t>(c.frame);
  w.put(c.next_output);
  w.put(c.next_gauge);
  w.put<std::int64_t>(c.removed_domain);
  w.put<std::int64_t>(c.removed_density);
  w.put<std::int64_t>(c.non_finite);
  w.put_vec(c.frame_times);
  w.put<std::uint64_t>(c.gauge_rows.size());
  for (const auto& r : c.gauge_rows) w.put_vec(r);
  const auto& p = c.particles;
  bool optional = false; // an optional field held (the SPS stress)
  particles::for_each_state_field(p, p, [&](const char*, const auto& v, const auto&, unsigned use, const auto*) {
    if (!(use & particles::kCheckpoint)) return;
    if (use & particles::kOptional)
      optional = optional || !v.empty();
    else
      w.put_vec(v);
  });
  w.put_vec(std::vector<char>(c.dem_state.begin(), c.dem_state.end()));
  w.put_vec(std::vector<char>(c.hazard_state.begin(), c.hazard_state.end()));
  // Version 4 adds the free bodies, version 5 the optional fields after them; without them
  // the bytes of version 3 (or 4) are written (the same checkpoint as before they existed).
  if (!c.body_state.empty() || optional) {
    w.bytes_[sizeof magic - 1] = '4';
    w.put_vec(std::vector<char>(c.body_state.begin(), c.body_state.end()));
  }
  if (optional) {
    w.bytes_[sizeof magic - 1] = '5';
    particles::for_each_state_field(p, p, [&](const char*, const auto& v, const auto&, unsigned use, const auto*) {
      if ((use & particles::kCheckpoint) && (use & particles::kOptional)) w.put_vec(v);
    });
  }
  write_file_atomic(path, w.bytes_);
}

Checkpoint read_checkpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the checkpoint (was the run started with this output folder?)");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string bytes = ss.str();
  // Versions 1 (before the DEM state) and 2 (before the hazard maps) are read too: the same
  // layout without them.
  const char version = bytes.size() >= sizeof magic && std::memcmp(bytes.data(), magic, sizeof magic - 1) == 0
                           ? bytes[sizeof magic - 1]
                           : '\0';
  if (version < '1' || version > '5') {
    if (version > '5')
      throw InputError(path, 0, "",
                       std::string("checkpoint version ") + version +
                           " is newer than this surge reads (5); restart it with the surge that wrote it");
    throw InputError(path, 0, "", "not a surge checkpoint");
  }
  const bool v1 = version == '1';
  Reader r(bytes, path);
  for (std::size_t k = 0; k < sizeof magic; ++k) (void)r.get<char>();
  if (r.get<std::uint32_t>() != sizeof(Real))
    throw InputError(path, 0, "", "checkpoint written by a build with another precision (Real)");
  Checkpoint c;
  c.time = r.get<double>();
  c.steps = r.get<std::int64_t>();
  c.frame = r.get<std::int32_t>();
  c.next_output = r.get<double>();
  c.next_gauge = r.get<double>();
  c.removed_domain = r.get<std::int64_t>();
  c.removed_density = r.get<std::int64_t>();
  c.non_finite = r.get<std::int64_t>();
  c.frame_times = r.get_vec<double>();
  const auto rows = r.get<std::uint64_t>();
  if (rows > bytes.size()) r.fail();
  for (std::uint64_t k = 0; k < rows; ++k) c.gauge_rows.push_back(r.get_vec<double>());
  auto& p = c.particles;
  particles::for_each_state_field(p, p, [&](const char*, auto& v, auto&, unsigned use, const auto*) {
    if ((use & particles::kCheckpoint) && !(use & particles::kOptional))
      v = r.get_vec<typename std::decay_t<decltype(v)>::value_type>();
  });
  if (!v1) {
    const auto dem = r.get_vec<char>();
    c.dem_state.assign(dem.begin(), dem.end());
  }
  if (version >= '3') {
    const auto hz = r.get_vec<char>();
    c.hazard_state.assign(hz.begin(), hz.end());
  }
  if (version >= '4') {
    const auto b = r.get_vec<char>();
    c.body_state.assign(b.begin(), b.end());
  }
  if (version >= '5')
    particles::for_each_state_field(p, p, [&](const char*, auto& v, auto&, unsigned use, const auto*) {
      if ((use & particles::kCheckpoint) && (use & particles::kOptional))
        v = r.get_vec<typename std::decay_t<decltype(v)>::value_type>();
    });
  const auto n = p.pos.size();
  bool sizes_agree = r.done();
  particles::for_each_state_field(p, p, [&](const char*, auto& v, auto&, unsigned use, const auto*) {
    if (use & particles::kOptional)
      sizes_agree = sizes_agree && (v.empty() || v.size() == n); // held or not
    else if (use & particles::kCheckpoint)
      sizes_agree = sizes_agree && v.size() == n;
    else
      v.assign(n, {}); // not checkpointed: recomputed (pressure)
  });
  if (!sizes_agree) r.fail();
  return c;
}

} // namespace surge::io
