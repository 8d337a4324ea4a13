#include "surge/io/case_reader.hpp"

#include "surge/core/error.hpp"
#include "surge/core/gauge_types.hpp"
#include "surge/core/number_rows.hpp"
#include "surge/io/case_schema.hpp"
#include "surge/motion/motion_law.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

namespace surge::io {
namespace {
// The folder of a case file, absolute (relative files in it are resolved against it).
std::filesystem::path case_dir(const std::string& file) {
  std::error_code ec;
  const auto abs = std::filesystem::absolute(std::filesystem::path(file), ec);
  return (ec ? std::filesystem::path(file) : abs).parent_path();
}

// Walks a YAML tree, remembering the file and the key path for messages.
class Reader {
public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Node& n, const std::string& key, const std::string& msg) const {
    int line = 0;
    if (n.IsDefined() && !n.Mark().is_null()) line = n.Mark().line + 1;
    std::string m = msg;
    if (overridden(key)) m += " (value given by --set " + key + ")";
    throw InputError(file_, line, key, m);
  }
  [[nodiscard]] bool overridden(const std::string& key) const {
    return std::any_of(set_keys_.begin(), set_keys_.end(), [&](const std::string& k) { return k == key; });
  }
  void note_override(const std::string& key) { set_keys_.push_back(key); }

  // Rejects keys not in `allowed` (typos), suggesting the closest allowed one.
  void check_keys(const YAML::Node& map, const std::string& path, const std::vector<std::string>& allowed) const {
    if (!map.IsMap()) fail(map, path, "expected a mapping (key: value pairs)");
    for (const auto& kv : map) {
      const auto k = kv.first.as<std::string>();
      bool ok = false;
      for (const auto& a : allowed) ok = ok || k == a;
      if (ok) continue;
      std::string best;
      std::size_t best_d = 3;
      for (const auto& a : allowed) {
        const std::size_t d = distance(k, a);
        if (d < best_d) {
          best_d = d;
          best = a;
        }
      }
      std::string msg = "unknown key";
      if (!best.empty())
        msg += " (did you mean '" + best + "'?)";
      else {
        msg += "; allowed here:";
        for (const auto& a : allowed) msg += " " + a;
      }
      fail(kv.first, join(path, k), msg);
    }
  }

  template <class T>
  T get(const YAML::Node& map, const std::string& path, const char* key, T fallback) const {
    const YAML::Node n = map[key];
    if (!n.IsDefined() || n.IsNull()) return fallback;
    return as<T>(n, join(path, key));
  }
  template <class T>
  T require(const YAML::Node& map, const std::string& path, const char* key) const {
    const YAML::Node n = map[key];
    if (!n.IsDefined() || n.IsNull()) fail(map, join(path, key), "is required");
    return as<T>(n, join(path, key));
  }

  template <class T>
  T as(const YAML::Node& n, const std::string& key) const {
    if constexpr (std::is_same_v<T, Vec3d>) {
      if (!n.IsSequence() || n.size() != 3) fail(n, key, "expected a list of three numbers, like [0, 0, 1]");
      return {as<double>(n[0], key), as<double>(n[1], key), as<double>(n[2], key)};
    } else {
      if (!n.IsScalar()) fail(n, key, std::string("expected ") + type_name<T>());
      try {
        T v = n.as<T>();
        if constexpr (std::is_floating_point_v<T>) {
          if (!std::isfinite(v)) fail(n, key, "must be a finite number");
        }
        return v;
      } catch (const YAML::Exception&) {
        fail(n, key, std::string("expected ") + type_name<T>() + ", got '" + n.Scalar() + "'");
      }
    }
  }

  static std::string join(const std::string& a, const std::string& b) { return a.empty() ? b : a + "." + b; }
  [[nodiscard]] const std::string& file() const { return file_; }

private:
  template <class T>
  static const char* type_name() {
    if constexpr (std::is_same_v<T, bool>)
      return "true or false";
    else if constexpr (std::is_integral_v<T>)
      return "an integer";
    else if constexpr (std::is_floating_point_v<T>)
      return "a number";
    else
      return "a string";
  }
  static std::size_t distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> d(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) d[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
      std::size_t prev = d[0];
      d[0] = i;
      for (std::size_t j = 1; j <= b.size(); ++j) {
        const std::size_t cur = d[j];
        d[j] = std::min({d[j] + 1, d[j - 1] + 1, prev + (a[i - 1] == b[j - 1] ? 0U : 1U)});
        prev = cur;
      }
    }
    return d[b.size()];
  }
  std::string file_;
  std::vector<std::string> set_keys_;
};

// Applies "a.b.c=value" to the tree; list elements are addressed by index ("fluid.0.box.min").
void apply_override(YAML::Node& root, const std::string& assignment, Reader& r) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set", 0, assignment, "expected KEY=VALUE, like --set dp=0.02");
  const std::string key = assignment.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw InputError("--set", 0, key, std::string("value is not valid YAML: ") + e.msg);
  }
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node cur = chain.back();
    if (cur.IsSequence()) {
      std::size_t idx = 0;
      try {
        idx = std::stoul(parts[i]);
      } catch (...) { throw InputError("--set", 0, key, "'" + parts[i] + "' should be a list index"); }
      if (idx >= cur.size()) throw InputError("--set", 0, key, "list index " + parts[i] + " out of range");
      chain.push_back(cur[idx]);
    } else {
      chain.push_back(cur[parts[i]]);
    }
  }
  YAML::Node parent = chain.back();
  if (parent.IsSequence()) {
    std::size_t idx = 0;
    try {
      idx = std::stoul(parts.back());
    } catch (...) { throw InputError("--set", 0, key, "'" + parts.back() + "' should be a list index"); }
    if (idx >= parent.size()) throw InputError("--set", 0, key, "list index out of range");
    parent[idx] = value;
  } else {
    parent[parts.back()] = value;
  }
  r.note_override(key);
}

// Reads the keys of one section declared in case_schema.cpp into s (absent keys keep
// s's value) and checks each against its range or choices.
template <class S>
void read_fields(const Reader& r, const YAML::Node& n, const std::string& path, const std::vector<Field<S>>& fields,
                 S& s) {
  for (const auto& f : fields) {
    const std::string key = Reader::join(path, f.key);
    std::visit(
        [&](auto m) {
          auto& v = s.*m;
          using V = std::decay_t<decltype(v)>;
          v = r.get(n, path, f.key, v);
          if constexpr (std::is_same_v<V, Vec3d> || std::is_same_v<V, bool>) {
            return; // any vector, any truth value
          } else if constexpr (std::is_same_v<V, std::string>) {
            if (f.choices.empty() || std::find(f.choices.begin(), f.choices.end(), v) != f.choices.end()) return;
            std::string list;
            for (std::size_t i = 0; i < f.choices.size(); ++i)
              list += (i == 0 ? "" : (i + 1 == f.choices.size() ? " or " : ", ")) + f.choices[i];
            r.fail(n[f.key], key, "must be " + list + " (" + f.help + ")");
          } else {
            if (!f.range.holds(static_cast<double>(v))) r.fail(n[f.key], key, f.range.message());
          }
        },
        f.member);
  }
}

Face parse_face(const Reader& r, const YAML::Node& n, const std::string& key) {
  const auto s = r.as<std::string>(n, key);
  constexpr Face all[] = {Face::XMin, Face::XMax, Face::YMin, Face::YMax, Face::ZMin, Face::ZMax};
  for (Face f : all)
    if (s == face_name(f)) return f;
  r.fail(n, key, "unknown face '" + s + "'; use xmin, xmax, ymin, ymax, zmin or zmax");
}

Box parse_box(const Reader& r, const YAML::Node& n, const std::string& path,
              const std::vector<std::string>& keys = {"min", "max"}) {
  r.check_keys(n, path, keys);
  Box b{r.require<Vec3d>(n, path, "min"), r.require<Vec3d>(n, path, "max")};
  for (int k = 0; k < 3; ++k)
    if (!(b.max[k] > b.min[k])) r.fail(n["max"], Reader::join(path, "max"), "every component of max must exceed min");
  return b;
}

// An absolute path for a file named in the case (relative to the case file's folder), so
// that the run folder's case.yaml names the same files wherever `surge restart` runs.
std::string resolve_file(const Reader& r, const YAML::Node& n, const std::string& key, const char* what) {
  std::filesystem::path p(r.as<std::string>(n, key));
  if (p.is_relative()) p = case_dir(r.file()) / p;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(p, ec)) r.fail(n, key, std::string(what) + "'" + p.string() + "' not found");
  return p.string();
}

// The items of a list under `key` of `parent`, each with its path ("walls.2"); nothing
// when the key is absent or empty.
template <class F>
void for_each_item(const Reader& r, const YAML::Node& parent, const std::string& key, const char* expected, F&& f) {
  const YAML::Node list = parent[key.substr(key.rfind('.') + 1)];
  if (!list.IsDefined() || list.IsNull()) return;
  if (!list.IsSequence()) r.fail(list, key, expected);
  for (std::size_t i = 0; i < list.size(); ++i) f(list[i], key + "." + std::to_string(i));
}

DemMaterialSpec parse_material(const Reader& r, const YAML::Node& m, const std::string& path,
                               const std::vector<DemMaterialSpec>& before) {
  r.check_keys(m, path, keys_under("dem.materials[]"));
  DemMaterialSpec ms;
  ms.line = m.Mark().line + 1;
  ms.name = r.require<std::string>(m, path, "name");
  for (const auto& other : before)
    if (other.name == ms.name) r.fail(m["name"], path + ".name", "duplicate material name");
  read_fields(r, m, path, material_fields(), ms);
  auto pair = [&](const char* key, double& k, double& kmax) {
    if (!m[key].IsDefined()) return;
    const auto v = m[key];
    if (!v.IsSequence() || v.size() != 2) r.fail(v, path + "." + key, "expected [stiffness factor, cap factor]");
    k = r.as<double>(v[0], path + "." + key);
    kmax = r.as<double>(v[1], path + "." + key);
    if (k < 0 || kmax < 0) r.fail(v, path + "." + key, "factors must not be negative");
  };
  pair("rolling", ms.k_roll, ms.k_roll_max);
  pair("twisting", ms.k_twist, ms.k_twist_max);
  if (const auto b = m["bond"]; b.IsDefined()) {
    r.check_keys(b, path + ".bond", {"cn", "cs"});
    ms.bonded = true;
    ms.bond_cn = r.require<double>(b, path + ".bond", "cn");
    ms.bond_cs = r.require<double>(b, path + ".bond", "cs");
    if (ms.bond_cn < 0 || ms.bond_cs < 0) r.fail(b, path + ".bond", "strengths must not be negative");
  }
  return ms;
}

// The index of the material an item names.
int material_of(const Reader& r, const YAML::Node& n, const std::string& path, const DemConfig& dem) {
  const auto name = r.require<std::string>(n, path, "material");
  for (std::size_t k = 0; k < dem.materials.size(); ++k)
    if (dem.materials[k].name == name) return static_cast<int>(k);
  r.fail(n["material"], path + ".material", "no DEM material named '" + name + "'");
}

MotionSpec parse_motion(const Reader& r, const YAML::Node& m, const std::string& path, const Case& c);
BodySpec parse_body(const Reader& r, const YAML::Node& b, const std::string& path, bool solid);

// A DEM wall's motion: a law, a free body (a closed mesh) or the motion of a moving SPH
// wall (`follows`), one of them.
void parse_dem_wall_motion(const Reader& r, const YAML::Node& w, const std::string& path, const Case& c,
                           DemWallSpec& ws) {
  const bool m = w["motion"].IsDefined(), b = w["body"].IsDefined(), f = w["follows"].IsDefined();
  if (int(m) + int(b) + int(f) > 1)
    r.fail(w, path, "a DEM wall moves by one of a law (motion), freely (body) or with an SPH wall (follows)");
  if ((m || b || f) && ws.terrain) r.fail(w, path, "a terrain does not move; give the moving part its own wall");
  if (m) ws.motion = parse_motion(r, w["motion"], path + ".motion", c);
  if (b) ws.body = parse_body(r, w["body"], path + ".body", ws.is_mesh);
  if (!f) return;
  ws.follows = r.as<std::string>(w["follows"], path + ".follows");
  const auto sw = std::find_if(c.walls.begin(), c.walls.end(), [&](const WallSpec& x) { return x.name == ws.follows; });
  if (sw == c.walls.end()) r.fail(w["follows"], path + ".follows", "no wall named '" + ws.follows + "'");
  if (!sw->moves())
    r.fail(w["follows"], path + ".follows",
           "the wall '" + ws.follows +
               "' does not move (give it a motion or a body; a still DEM wall needs no follows)");
}

DemWallSpec parse_dem_wall(const Reader& r, const YAML::Node& w, const std::string& path, const Case& c) {
  const DemConfig& dem = c.dem;
  r.check_keys(w, path, keys_under("dem.walls[]"));
  DemWallSpec ws;
  read_fields(r, w, path, dem_wall_fields(), ws);
  ws.line = w.Mark().line + 1;
  ws.material = material_of(r, w, path, dem);
  if (int(w["plane"].IsDefined()) + int(w["mesh"].IsDefined()) + int(w["terrain"].IsDefined()) != 1)
    r.fail(w, path, "a DEM wall needs exactly one of 'plane', 'mesh' (an STL file) or 'terrain' (an elevation grid)");
  if (const auto pl = w["plane"]; pl.IsDefined()) {
    r.check_keys(pl, path + ".plane", {"point", "normal"});
    ws.point = r.require<Vec3d>(pl, path + ".plane", "point");
    ws.normal = r.require<Vec3d>(pl, path + ".plane", "normal");
    if (!(norm(ws.normal) > 0)) r.fail(pl["normal"], path + ".plane.normal", "must not be zero");
  } else {
    const char* key = w["mesh"].IsDefined() ? "mesh" : "terrain";
    ws.is_mesh = true;
    ws.terrain = w["terrain"].IsDefined();
    ws.mesh_path = resolve_file(r, w[key], path + "." + key, "file ");
  }
  parse_dem_wall_motion(r, w, path, c, ws);
  return ws;
}

// radius, and radius_min at most radius.
void read_radius(const Reader& r, const YAML::Node& pk, const std::string& path, DemPackSpec& ps) {
  ps.radius = r.require<double>(pk, path, "radius");
  if (!(ps.radius > 0)) r.fail(pk["radius"], path + ".radius", "must be positive");
  if (ps.radius_min > ps.radius)
    r.fail(pk["radius_min"], path + ".radius_min",
           "must not exceed radius (the largest radius, which sets the spacing)");
}

DemPackSpec parse_pack(const Reader& r, const YAML::Node& pk, const std::string& path, const Case& c) {
  r.check_keys(pk, path, keys_under("dem.packs[]"));
  DemPackSpec ps;
  ps.line = pk.Mark().line + 1;
  ps.material = material_of(r, pk, path, c.dem);
  read_fields(r, pk, path, pack_fields(), ps);
  const int regions = (pk["box"].IsDefined() ? 1 : 0) + (pk["mesh"].IsDefined() ? 1 : 0) +
                      (pk["csv"].IsDefined() ? 1 : 0) + (pk["between"].IsDefined() ? 1 : 0);
  if (regions != 1)
    r.fail(pk, path, "a pack needs exactly one of 'box', 'mesh' (a closed STL), 'between' (two grids) or 'csv'");
  if (ps.random_count > 0 && ps.jitter > 0) r.fail(pk, path, "'jitter' moves a lattice; a 'random' pack has none");
  if (const auto bt = pk["between"]; bt.IsDefined()) {
    r.check_keys(bt, path + ".between", {"top", "bottom"});
    if (!bt["top"].IsDefined() || !bt["bottom"].IsDefined())
      r.fail(bt, path + ".between", "needs 'top' (the pre-failure surface) and 'bottom' (the sliding surface)");
    ps.top_path = resolve_file(r, bt["top"], path + ".between.top", "elevation grid ");
    ps.bottom_path = resolve_file(r, bt["bottom"], path + ".between.bottom", "elevation grid ");
    read_radius(r, pk, path, ps);
    return ps;
  }
  if (pk["csv"].IsDefined()) {
    if (ps.random_count > 0 || ps.jitter > 0 || ps.radius_min > 0)
      r.fail(pk, path, "'random', 'jitter' and 'radius_min' do not apply to a CSV list (it gives each radius)");
    ps.from_csv = true;
    ps.csv = resolve_file(r, pk["csv"], path + ".csv", "file ");
    return ps;
  }
  if (pk["box"].IsDefined()) {
    ps.box = parse_box(r, pk["box"], path + ".box");
    if (!c.domain.contains(ps.box.min, 1e-9) || !c.domain.contains(ps.box.max, 1e-9))
      r.fail(pk["box"], path + ".box", "the pack lies (partly) outside the domain");
  } else {
    ps.mesh_path = resolve_file(r, pk["mesh"], path + ".mesh", "file ");
  }
  read_radius(r, pk, path, ps);
  if (pk["box"].IsDefined())
    for (int k = 0; k < 3; ++k)
      if (ps.box.max[k] - ps.box.min[k] < 2 * ps.radius)
        r.fail(pk["box"], path + ".box", "the box is thinner than one sphere diameter");
  return ps;
}

void parse_dem(const Reader& r, const YAML::Node& d, Case& c) {
  r.check_keys(d, "dem", keys_under("dem"));
  auto& dem = c.dem;
  read_fields(r, d, "dem", dem_fields(), dem);
  const YAML::Node mats = d["materials"];
  if (!mats.IsDefined() || !mats.IsSequence() || mats.size() == 0)
    r.fail(mats.IsDefined() ? mats : d, "dem.materials", "a list of at least one material is required");
  for_each_item(r, d, "dem.materials", "", [&](const YAML::Node& m, const std::string& path) {
    dem.materials.push_back(parse_material(r, m, path, dem.materials));
  });
  for_each_item(r, d, "dem.walls", "expected a list of walls", [&](const YAML::Node& w, const std::string& path) {
    dem.walls.push_back(parse_dem_wall(r, w, path, c));
  });
  for_each_item(
      r, d, "dem.packs", "expected a list of sphere packs",
      [&](const YAML::Node& pk, const std::string& path) { dem.packs.push_back(parse_pack(r, pk, path, c)); });
}

// fluid[].particles: the table's particles, each inside the domain; the region's box their
// bounds grown by dp/2 within the domain.
void read_given_particles(const Reader& r, const YAML::Node& n, const std::string& key, const Case& c,
                          FluidRegion& reg) {
  reg.particles = resolve_file(r, n, key, "particle table ");
  const auto rows = read_number_rows(reg.particles, 6, 7, "x, y, z, vx, vy, vz[, rho]", "particle table");
  const Vec3d first{rows[0].v[0], rows[0].v[1], rows[0].v[2]};
  Box bounds{first, first};
  for (const auto& row : rows) {
    const Vec3d x{row.v[0], row.v[1], row.v[2]};
    if (!c.domain.contains(x, 1e-9))
      throw InputError(reg.particles, row.line, "", "the particle lies outside the domain");
    const double rho = row.v.size() == 7 ? row.v[6] : 0;
    if (row.v.size() == 7 && !(rho > 0)) throw InputError(reg.particles, row.line, "", "rho must be positive");
    reg.given_pos.push_back(x);
    reg.given_vel.push_back({row.v[3], row.v[4], row.v[5]});
    reg.given_rho.push_back(rho);
    for (int k = 0; k < 3; ++k) {
      bounds.min[k] = std::min(bounds.min[k], x[k]);
      bounds.max[k] = std::max(bounds.max[k], x[k]);
    }
  }
  for (int k = 0; k < 3; ++k) {
    reg.box.min[k] = std::max(c.domain.min[k], bounds.min[k] - c.dp / 2);
    reg.box.max[k] = std::min(c.domain.max[k], bounds.max[k] + c.dp / 2);
  }
}

FluidRegion parse_fluid(const Reader& r, const YAML::Node& f, const std::string& path, const Case& c) {
  r.check_keys(f, path, keys_under("fluid[]"));
  FluidRegion reg;
  if ((f["box"].IsDefined() ? 1 : 0) + (f["reservoir"].IsDefined() ? 1 : 0) + (f["particles"].IsDefined() ? 1 : 0) != 1)
    r.fail(f, path, "a fluid region needs exactly one of 'box', 'reservoir' or 'particles'");
  read_fields(r, f, path, fluid_fields(), reg);
  reg.line = f.Mark().line + 1;
  if (f["fill"].IsDefined() && !f["box"].IsDefined())
    r.fail(f["fill"], path + ".fill",
           "'fill' is a box's (a reservoir fills its lake on the lattice, a particle table is placed as given)");
  if (f["particles"].IsDefined()) {
    read_given_particles(r, f["particles"], path + ".particles", c, reg);
    return reg;
  }
  if (const auto res = f["reservoir"]; res.IsDefined()) {
    const std::string rp = path + ".reservoir";
    r.check_keys(res, rp, {"level", "seed"});
    reg.reservoir = true;
    reg.level = r.require<double>(res, rp, "level");
    const auto seed = res["seed"];
    if (!seed.IsDefined() || !seed.IsSequence() || seed.size() != 2)
      r.fail(seed.IsDefined() ? seed : res, rp + ".seed", "expected [x, y]: a point of the lake");
    reg.seed_x = r.as<double>(seed[0], rp + ".seed");
    reg.seed_y = r.as<double>(seed[1], rp + ".seed");
    const Box& d = c.domain;
    if (!(reg.level > d.min.z + c.dp))
      r.fail(res["level"], rp + ".level", "the level lies below the domain's bottom (plus dp): no water fits");
    if (reg.level > d.max.z)
      r.fail(res["level"], rp + ".level", "the level lies above the domain's top; raise domain.max.z");
    if (reg.seed_x < d.min.x || reg.seed_x > d.max.x || reg.seed_y < d.min.y || reg.seed_y > d.max.y)
      r.fail(res["seed"], rp + ".seed", "the seed point lies outside the domain");
    reg.box = {d.min, {d.max.x, d.max.y, reg.level}};
    return reg;
  }
  reg.box = parse_box(r, f["box"], path + ".box");
  if (!c.domain.contains(reg.box.min, 1e-9) || !c.domain.contains(reg.box.max, 1e-9))
    r.fail(f["box"], path + ".box", "fluid region lies (partly) outside the domain; enlarge domain or move the water");
  const auto cells = [&](int k) { return std::floor((reg.box.max[k] - reg.box.min[k]) / c.dp + 1e-3); };
  if (cells(0) < 1 || cells(1) < 1 || cells(2) < 1)
    r.fail(f["box"], path + ".box", "fluid region is thinner than dp and would hold no particle");
  return reg;
}

// The keys a motion law reads besides law, start and pivot (its registry entry).
std::vector<std::string> law_keys(const motion::LawEntry& e) {
  std::vector<std::string> k = e.required;
  k.insert(k.end(), e.optional.begin(), e.optional.end());
  return k;
}

// walls[].motion: the law by name, the keys it needs and no others; the law is built once
// here (a time series' file is read and checked) so that a bad motion fails before a run.
MotionSpec parse_motion(const Reader& r, const YAML::Node& m, const std::string& path, const Case& c) {
  r.check_keys(m, path, keys_under("walls[].motion"));
  MotionSpec s;
  s.line = m.Mark().line + 1;
  s.law = r.require<std::string>(m, path, "law");
  const motion::LawEntry* e = motion::find_law(s.law);
  if (!e) {
    std::string known;
    for (const auto& l : motion::motion_laws()) known += (known.empty() ? "" : ", ") + std::string(l.name);
    r.fail(m["law"], path + ".law", "unknown motion law '" + s.law + "'; the laws are " + known);
  }
  read_fields(r, m, path, motion_fields(), s);
  const std::vector<std::string> takes = law_keys(*e);
  for (const auto& kv : m) {
    const auto k = kv.first.as<std::string>();
    if (k == "law" || k == "start" || k == "pivot" || std::find(takes.begin(), takes.end(), k) != takes.end()) continue;
    std::string list = "start, pivot";
    for (const auto& t : takes) list.append(", ").append(t);
    r.fail(kv.first, std::string(path).append(".").append(k),
           "does not apply to the law " + s.law + " (it reads " + list + ")");
  }
  for (const auto& k : e->required)
    if (!m[k].IsDefined()) r.fail(m, std::string(path).append(".").append(k), "is required by the motion law " + s.law);
  if (m["pivot"].IsDefined()) {
    s.pivot = r.as<Vec3d>(m["pivot"], path + ".pivot");
    s.pivot_given = true;
  }
  if (m["csv"].IsDefined()) {
    s.csv = r.as<std::string>(m["csv"], path + ".csv");
    s.csv_path = resolve_file(r, m["csv"], path + ".csv", "time series ");
  }
  (void)motion::Motion(s, motion::MotionContext{c.g(), r.file(), path});
  return s;
}

// walls[].body: a free rigid body, a solid box or a closed mesh with a mass or a density.
// solid: the wall is a solid box or a closed mesh (the reader cannot tell a closed mesh
// from an open one; mass_properties refuses one that encloses no volume).
BodySpec parse_body(const Reader& r, const YAML::Node& b, const std::string& path, bool solid) {
  r.check_keys(b, path, keys_under("walls[].body"));
  BodySpec s;
  s.free = true;
  s.line = b.Mark().line + 1;
  read_fields(r, b, path, body_fields(), s);
  if ((s.mass > 0) == (s.density > 0))
    r.fail(b, path, "a free body needs its mass or its density (one of them, positive)");
  if (!solid) r.fail(b, path, "a free body is a solid box (solid: true) or a closed mesh, not a tank or a terrain");
  if (s.constraint == "line" && !(norm(s.direction) > 0))
    r.fail(b["direction"], path + ".direction", "must not be zero");
  if (s.constraint == "line" && norm(s.spin) > 0)
    r.fail(b["spin"], path + ".spin", "a body on a line does not turn; spin applies to constraint: none");
  if (s.constraint != "line" && (s.mu_static > 0 || s.mu_kinetic > 0))
    r.fail(b, path, "friction (mu_static, mu_kinetic) acts against a rail: give constraint: line");
  if (s.inertia.x < 0 || s.inertia.y < 0 || s.inertia.z < 0 ||
      (norm(s.inertia) > 0 && !(s.inertia.x > 0 && s.inertia.y > 0 && s.inertia.z > 0)))
    r.fail(b["inertia"], path + ".inertia", "principal moments must all be positive (or all 0: from the shape)");
  return s;
}

WallSpec parse_wall(const Reader& r, const YAML::Node& w, const std::string& path, std::size_t i, const Case& c) {
  r.check_keys(w, path, keys_under("walls[]"));
  WallSpec ws;
  ws.name = r.get<std::string>(w, path, "name", "wall" + std::to_string(i));
  ws.line = w.Mark().line + 1;
  read_fields(r, w, path, wall_fields(), ws);
  const bool has_box = w["box"].IsDefined(), has_mesh = w["mesh"].IsDefined(), has_terrain = w["terrain"].IsDefined();
  if (int(has_box) + int(has_mesh) + int(has_terrain) != 1)
    r.fail(w, path, "a wall needs exactly one of 'box', 'mesh' (an STL file) or 'terrain' (an elevation grid)");
  if (has_box) {
    ws.box = parse_box(r, w["box"], path + ".box");
    if (const auto o = w["open"]; o.IsDefined()) {
      if (!o.IsSequence()) r.fail(o, path + ".open", "expected a list of faces, like [zmax]");
      for (std::size_t k = 0; k < o.size(); ++k) ws.open.push_back(parse_face(r, o[k], path + ".open"));
    }
  } else {
    if (w["open"].IsDefined()) r.fail(w["open"], path + ".open", "'open' applies to box walls only");
    // A solid mesh: everything behind its surface (negative signed distance) is wall,
    // so no water is made there (a slope with ground under it).
    // A terrain has the ground under it: solid whatever the case says.
    const char* key = has_mesh ? "mesh" : "terrain";
    ws.is_mesh = true;
    ws.terrain = has_terrain;
    ws.solid = ws.solid || has_terrain;
    ws.mesh = r.as<std::string>(w[key], path + "." + key);
    ws.mesh_path = resolve_file(r, w[key], path + "." + key, has_mesh ? "mesh file " : "elevation grid ");
  }
  for (const auto& other : c.walls)
    if (other.name == ws.name) r.fail(w, path + ".name", "duplicate wall name '" + ws.name + "'");
  if (w["motion"].IsDefined()) {
    if (ws.terrain) r.fail(w["motion"], path + ".motion", "a terrain does not move; give the moving part its own wall");
    ws.motion = parse_motion(r, w["motion"], path + ".motion", c);
  }
  if (w["body"].IsDefined()) {
    if (w["motion"].IsDefined())
      r.fail(w["body"], path + ".body", "a wall moves either by a law (motion) or freely (body), not both");
    ws.body = parse_body(r, w["body"], path + ".body", !ws.terrain && (ws.is_mesh || ws.solid));
  }
  return ws;
}

// Water must not overlap a tank's wall layers: a fluid box is either inside a box tank
// or clear of it.
void check_fluid_in_tanks(const Reader& r, const YAML::Node& root, const Case& c) {
  for (std::size_t i = 0; i < c.fluid.size(); ++i) {
    if (c.fluid[i].reservoir || c.fluid[i].given()) continue; // bounded by the walls themselves; as the user gives it
    const Box& f = c.fluid[i].box;
    for (const auto& w : c.walls) {
      if (w.is_mesh || w.solid) continue;
      const Box& t = w.box;
      const bool inside = t.contains(f.min, 1e-9) && t.contains(f.max, 1e-9);
      bool apart = false;
      for (int k = 0; k < 3; ++k) apart = apart || f.max[k] <= t.min[k] + 1e-9 || f.min[k] >= t.max[k] - 1e-9;
      if (!inside && !apart)
        r.fail(root["fluid"][i]["box"], "fluid." + std::to_string(i) + ".box",
               "water crosses the walls of '" + w.name + "' (line " + std::to_string(w.line) +
                   "); put the fluid box inside the tank");
    }
  }
}

// domain.periodic: faces in pairs, each period at least two kernel radii long (an image
// band of one interaction reach must not reach past the next period but one).
void parse_periodic(const Reader& r, const YAML::Node& d, Case& c) {
  const auto p = d["periodic"];
  if (!p.IsDefined()) return;
  if (!p.IsSequence()) r.fail(p, "domain.periodic", "expected a list of faces in pairs, like [ymin, ymax]");
  std::array<int, 6> given{};
  for (std::size_t k = 0; k < p.size(); ++k) ++given[static_cast<std::size_t>(parse_face(r, p[k], "domain.periodic"))];
  for (std::size_t a = 0; a < 3; ++a) {
    const int lo = given[2 * a], hi = given[2 * a + 1];
    if (lo > 1 || hi > 1) r.fail(p, "domain.periodic", "a face is listed twice");
    if (lo != hi)
      r.fail(p, "domain.periodic",
             std::string("periodic faces come in pairs: '") + face_name(static_cast<Face>(2 * a + (lo ? 0 : 1))) +
                 "' needs '" + face_name(static_cast<Face>(2 * a + (lo ? 1 : 0))) + "'");
    if (!lo) continue;
    const double len = c.domain.max[static_cast<int>(a)] - c.domain.min[static_cast<int>(a)];
    const double radius = 2 * c.h(); // the Wendland kernel's support
    if (len < 2 * radius * (1 - 1e-9)) {
      std::ostringstream m;
      m << "the domain is " << len << " m long along "
        << "xyz"[a] << ": a periodic length must be at least two kernel radii (4 h = " << 2 * radius << " m)";
      r.fail(p, "domain.periodic", m.str());
    }
    c.periodic[a] = true;
  }
}

// domain.symmetry: any faces, none of them periodic too.
void parse_symmetry(const Reader& r, const YAML::Node& d, Case& c) {
  const auto p = d["symmetry"];
  if (!p.IsDefined()) return;
  if (!p.IsSequence()) r.fail(p, "domain.symmetry", "expected a list of faces, like [ymax]");
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Face f = parse_face(r, p[k], "domain.symmetry");
    const auto i = static_cast<std::size_t>(f);
    if (c.symmetry[i]) r.fail(p[k], "domain.symmetry", "a face is listed twice");
    if (c.periodic[i / 2])
      r.fail(p[k], "domain.symmetry", std::string("'") + face_name(f) + "' is periodic already (domain.periodic)");
    c.symmetry[i] = true;
  }
}

// damping: zones at domain faces that are neither periodic nor symmetry, each shorter than
// the domain along its axis, one per face.
DampingSpec parse_damping(const Reader& r, const YAML::Node& n, const std::string& path, const Case& c) {
  r.check_keys(n, path, keys_under("damping[]"));
  DampingSpec d;
  d.line = n.Mark().is_null() ? 0 : n.Mark().line + 1;
  if (!n["face"].IsDefined())
    r.fail(n, Reader::join(path, "face"), "is required (xmin, xmax, ymin, ymax, zmin or zmax)");
  d.face = parse_face(r, n["face"], Reader::join(path, "face"));
  d.length = r.require<double>(n, path, "length");
  d.rate = r.get(n, path, "rate", d.rate);
  const auto f = static_cast<int>(d.face);
  const int a = f / 2;
  const double extent = c.domain.max[a] - c.domain.min[a];
  if (!(d.length > 0) || !(d.length < extent)) {
    std::ostringstream m;
    m << "must be positive and shorter than the domain along "
      << "xyz"[a] << " (" << extent << " m)";
    r.fail(n["length"], Reader::join(path, "length"), m.str());
  }
  if (!(d.rate > 0) || !std::isfinite(d.rate)) r.fail(n["rate"], Reader::join(path, "rate"), "must be positive [1/s]");
  if (c.image_face(f))
    r.fail(n["face"], Reader::join(path, "face"),
           std::string("'") + face_name(d.face) + "' is a periodic or symmetry face: water there is not to be damped");
  const int opposite = f ^ 1;
  if (c.symmetry[static_cast<std::size_t>(opposite)] && d.length > extent / 2)
    r.fail(n["length"], Reader::join(path, "length"),
           std::string("reaches past the middle towards the symmetry face ") + face_name(static_cast<Face>(opposite)));
  for (const DampingSpec& o : c.damping)
    if (o.face == d.face) r.fail(n["face"], Reader::join(path, "face"), "a damping zone at this face is given already");
  return d;
}

// Walls and water end at a periodic or symmetry face (the images supply the rest): nothing
// of them may lie beyond one, and a box tank leaves such faces open.
void check_within_image_faces(const Reader& r, const YAML::Node& root, const Case& c) {
  if (!c.any_periodic() && !c.any_symmetry()) return;
  const double tol = 1e-9 * (1 + norm(c.domain.max - c.domain.min));
  for (int face = 0; face < 6; ++face) {
    if (!c.image_face(face)) continue;
    const int a = face / 2;
    const bool hi = face % 2 == 1;
    const std::string what = c.periodic[static_cast<std::size_t>(a)] ? "periodic" : "symmetry";
    const auto beyond = [&](const Box& b) {
      return hi ? b.max[a] > c.domain.max[a] + tol : b.min[a] < c.domain.min[a] - tol;
    };
    const std::string where = std::string(" beyond the ") + what + " face " + face_name(static_cast<Face>(face));
    for (std::size_t i = 0; i < c.fluid.size(); ++i)
      if (!c.fluid[i].reservoir && beyond(c.fluid[i].box))
        r.fail(root["fluid"][i]["box"], "fluid." + std::to_string(i) + ".box",
               "water reaches" + where + " (the images supply what lies beyond; end the box at the face)");
    for (std::size_t i = 0; i < c.walls.size(); ++i) {
      const WallSpec& w = c.walls[i];
      const std::string key = "walls." + std::to_string(i);
      if (w.is_mesh)
        r.fail(root["walls"][i], key,
               "meshes and terrains are not yet allowed with periodic or symmetry faces (their wall layers cross "
               "them); use box walls");
      if (beyond(w.box)) r.fail(root["walls"][i]["box"], key + ".box", "the wall reaches" + where);
      if (w.solid) continue;
      const auto f = static_cast<Face>(face);
      if (std::find(w.open.begin(), w.open.end(), f) == w.open.end())
        r.fail(root["walls"][i], key + ".open",
               std::string("a tank at a ") + what + " face leaves it open: add " + face_name(f) +
                   " to 'open' (its wall layers would lie beyond it)");
    }
  }
}

// DEM walls with periodic or symmetry faces: planes along those axes (a plane across a
// periodic axis would cut the period; one slanted across a symmetry face would meet its
// own image, which the spheres do not see), no meshes yet (their triangles would need
// images); not both kinds of face at once.
void check_dem_image_faces(const Reader& r, const YAML::Node& root, const Case& c) {
  if (c.any_periodic() && c.any_symmetry())
    r.fail(root["domain"]["symmetry"], "domain.symmetry",
           "DEM spheres with both periodic and symmetry faces are not yet possible");
  for (std::size_t i = 0; i < c.dem.walls.size(); ++i) {
    const DemWallSpec& w = c.dem.walls[i];
    const std::string key = "dem.walls." + std::to_string(i);
    if (w.is_mesh)
      r.fail(root["dem"]["walls"][i], key,
             "DEM meshes and terrains are not yet allowed with periodic or symmetry faces (their triangles would "
             "need images); use planes");
    const Vec3d n = w.normal * (1.0 / norm(w.normal));
    for (std::size_t a = 0; a < 3; ++a) {
      const bool mirror = c.symmetry[2 * a] || c.symmetry[2 * a + 1];
      if ((c.periodic[a] || mirror) && std::fabs(n[static_cast<int>(a)]) > 1e-9)
        r.fail(root["dem"]["walls"][i]["normal"], key + ".normal",
               std::string("a DEM plane facing along the ") + (mirror ? "symmetry" : "periodic") + " axis " + "xyz"[a] +
                   (mirror ? " would meet its own mirror image" : " would cut the period") +
                   ": planes lie along the axes of periodic and symmetry faces");
    }
  }
}

// The component a gauge reads, checked against its type's choices (core/gauge_types.hpp).
void parse_component(const Reader& r, const YAML::Node& g, const std::string& path, GaugeSpec& gs) {
  const GaugeTypeInfo& t = gauge_type(gs.type);
  if (*t.components == 0) {
    if (g["component"].IsDefined()) {
      std::string with;
      for (const auto& x : gauge_types)
        if (*x.components) with += (with.empty() ? "" : ", ") + std::string(x.name);
      r.fail(g["component"], path + ".component", "applies to " + with + " gauges only");
    }
    return;
  }
  gs.component = r.get<std::string>(g, path, "component", t.default_component);
  if (!gauge_reads(t, gs.component)) r.fail(g["component"], path + ".component", t.help);
}

GaugeType parse_gauge_type(const Reader& r, const YAML::Node& g, const std::string& path) {
  const auto type = r.require<std::string>(g, path, "type");
  for (const auto& t : gauge_types)
    if (type == t.name) return t.type;
  r.fail(g["type"], path + ".type", "unknown gauge type '" + type + "'; use " + gauge_type_list(", ", " or "));
}

GaugeSpec parse_gauge(const Reader& r, const YAML::Node& g, const std::string& path, const Case& c,
                      std::set<std::string>& names) {
  r.check_keys(g, path, keys_under("gauges[]"));
  GaugeSpec gs;
  gs.line = g.Mark().line + 1;
  gs.name = r.require<std::string>(g, path, "name");
  if (gs.name.empty() || gs.name.find_first_of(",\"\n") != std::string::npos || gs.name == "time")
    r.fail(g["name"], path + ".name", "gauge names must be non-empty, not 'time', without commas or quotes");
  if (!names.insert(gs.name).second) r.fail(g["name"], path + ".name", "duplicate gauge name");
  read_fields(r, g, path, gauge_fields(), gs);
  gs.type = parse_gauge_type(r, g, path);
  switch (gs.type) {
  case GaugeType::Height:
    gs.x = r.require<double>(g, path, "x");
    gs.y = r.require<double>(g, path, "y");
    if (!c.domain.contains({gs.x, gs.y, c.domain.min.z})) r.fail(g, path, "height gauge lies outside the domain");
    break;
  case GaugeType::Pressure:
  case GaugeType::Velocity:
    gs.at = r.require<Vec3d>(g, path, "at");
    if (!c.domain.contains(gs.at)) r.fail(g["at"], path + ".at", "gauge point lies outside the domain");
    break;
  case GaugeType::Force:
    gs.wall = r.require<std::string>(g, path, "wall");
    if (std::none_of(c.walls.begin(), c.walls.end(), [&](const WallSpec& w) { return w.name == gs.wall; }))
      r.fail(g["wall"], path + ".wall", "no wall named '" + gs.wall + "'");
    break;
  case GaugeType::Sphere:
    gs.sphere = r.require<int>(g, path, "sphere");
    if (gs.sphere < 0) r.fail(g["sphere"], path + ".sphere", "must not be negative");
    break;
  case GaugeType::DemWall:
    gs.wall = r.require<std::string>(g, path, "wall"); // checked once the DEM walls are read
    break;
  case GaugeType::Body: {
    gs.wall = r.require<std::string>(g, path, "wall");
    const auto w = std::find_if(c.walls.begin(), c.walls.end(), [&](const WallSpec& x) { return x.name == gs.wall; });
    if (w == c.walls.end()) break; // a DEM wall's, checked once the DEM walls are read
    if (!w->moves())
      r.fail(g["wall"], path + ".wall", "the wall '" + gs.wall + "' does not move (a force gauge reads a still wall)");
    break;
  }
  }
  parse_component(r, g, path, gs);
  return gs;
}

// Refuses cases too large to build before allocating anything: fluid volume plus box-wall
// shells, in particles.
void check_size(const Reader& r, const YAML::Node& root, const Case& c) {
  double n = 0;
  for (const auto& f : c.fluid)
    n += (f.box.max.x - f.box.min.x) * (f.box.max.y - f.box.min.y) * (f.box.max.z - f.box.min.z) / (c.dp * c.dp * c.dp);
  for (const auto& w : c.walls) {
    if (w.is_mesh) continue;
    const Vec3d e = w.box.max - w.box.min;
    n += 2 * (e.x * e.y + e.y * e.z + e.x * e.z) * 3 * c.sph.h_over_dp / (c.dp * c.dp);
  }
  if (n > 1.5e9) {
    std::ostringstream m;
    m << "about " << n << " particles: more than surge can hold (1.5e9); increase dp";
    r.fail(root["dp"], "dp", m.str());
  }
}

// What only the whole case can tell: gauges naming DEM walls, water gauges without water,
// nothing to simulate, a speed of sound that cannot be derived.
// [x, y] inside the domain's x-y extent.
std::pair<double, double> parse_xy(const Reader& r, const YAML::Node& n, const std::string& key, const Case& c) {
  if (!n.IsDefined() || !n.IsSequence() || n.size() != 2) r.fail(n, key, "expected [x, y]");
  const double x = r.as<double>(n[0], key), y = r.as<double>(n[1], key);
  if (x < c.domain.min.x || x > c.domain.max.x || y < c.domain.min.y || y > c.domain.max.y)
    r.fail(n, key, "the point lies outside the domain");
  return {x, y};
}

void parse_hazard(const Reader& r, const YAML::Node& hz, Case& c) {
  r.check_keys(hz, "hazard", keys_under("hazard"));
  HazardConfig& h = c.hazard;
  h.enabled = true;
  h.line = hz.Mark().line + 1;
  read_fields(r, hz, "hazard", hazard_fields(), h);
  if (std::none_of(c.walls.begin(), c.walls.end(), [](const WallSpec& w) { return w.terrain; }))
    r.fail(hz, "hazard", "hazard maps lie on a terrain's grid: the case needs a wall with 'terrain'");
  const auto res = std::find_if(c.fluid.begin(), c.fluid.end(), [](const FluidRegion& f) { return f.reservoir; });
  if (hz["still_level"].IsDefined())
    h.still_level = r.as<double>(hz["still_level"], "hazard.still_level");
  else if (res != c.fluid.end())
    h.still_level = res->level;
  else
    r.fail(hz, "hazard.still_level", "is required when no reservoir gives the level of the water at rest");
  std::set<std::string> names;
  for_each_item(r, hz, "hazard.run_up", "expected a list of lines, like [{name: far, from: [x, y], to: [x, y]}]",
                [&](const YAML::Node& l, const std::string& path) {
                  r.check_keys(l, path, keys_under("hazard.run_up[]"));
                  RunUpLine ln;
                  ln.line = l.Mark().line + 1;
                  ln.name = r.require<std::string>(l, path, "name");
                  if (ln.name.empty() || ln.name.find(',') != std::string::npos || !names.insert(ln.name).second)
                    r.fail(l["name"], path + ".name", "must be a unique name without commas");
                  std::tie(ln.x0, ln.y0) = parse_xy(r, l["from"], path + ".from", c);
                  std::tie(ln.x1, ln.y1) = parse_xy(r, l["to"], path + ".to", c);
                  h.run_up.push_back(ln);
                });
}

void check_whole(const Reader& r, const YAML::Node& root, const Case& c) {
  for (std::size_t i = 0; i < c.gauges.size(); ++i) {
    const GaugeSpec& g = c.gauges[i];
    if (g.type != GaugeType::DemWall) continue;
    if (std::none_of(c.dem.walls.begin(), c.dem.walls.end(), [&](const DemWallSpec& w) { return w.name == g.wall; }))
      r.fail(root["gauges"][i]["wall"], "gauges." + std::to_string(i) + ".wall",
             "no DEM wall named '" + g.wall + "' (give the wall a name: under dem.walls)");
  }
  for (std::size_t i = 0; i < c.gauges.size(); ++i) {
    const GaugeSpec& g = c.gauges[i];
    if (g.type != GaugeType::Body || c.wall_named(g.wall)) continue;
    const DemWallSpec* w = c.dem_wall_named(g.wall);
    if (!w)
      r.fail(root["gauges"][i]["wall"], "gauges." + std::to_string(i) + ".wall", "no wall named '" + g.wall + "'");
    if (!w->motion.moves() && !w->body.free)
      r.fail(root["gauges"][i]["wall"], "gauges." + std::to_string(i) + ".wall",
             "the DEM wall '" + g.wall + "' " +
                 (w->follows.empty() ? "does not move (a dem_wall gauge reads a still wall)"
                                     : "follows '" + w->follows + "': name that wall"));
  }
  if (c.dem.active() && c.fluid.empty())
    for (std::size_t i = 0; i < c.gauges.size(); ++i)
      if (gauge_type(c.gauges[i].type).water)
        r.fail(root["gauges"][i], "gauges." + std::to_string(i),
               "this gauge measures the water and a DEM-only case has none; use sphere, dem_wall or body gauges");
  if ((c.any_periodic() || c.any_symmetry()) && c.dem.active()) check_dem_image_faces(r, root, c);
  if (c.fluid.empty() && c.walls.empty() && !c.dem.active())
    r.fail(root, "fluid", "the case has neither fluid, walls nor DEM spheres: nothing to simulate");
  if (!c.fluid.empty() && !(c.water_depth() > 0))
    r.fail(root, "sph.hmax", "cannot derive the water depth; set sph.hmax");
  if (!c.fluid.empty() && !(c.sound_speed() > 0))
    r.fail(root["gravity"], "gravity", "with zero gravity the speed of sound must be given as sph.c0");
}

// A keyed section (time, sph, coupling) read from its table.
template <class S>
void parse_section(const Reader& r, const YAML::Node& root, const std::string& key, const std::vector<Field<S>>& fields,
                   S& s) {
  const auto n = root[key];
  if (!n.IsDefined()) return;
  r.check_keys(n, key, keys_under(key));
  read_fields(r, n, key, fields, s);
}

// alpha is the artificial viscosity's coefficient, and the default viscosity is laminar
// (since issue 35): a case written for the paper's scheme that sets alpha and leaves the
// viscosity out would run with another viscosity than its author meant, so it must name it.
void check_alpha_has_its_viscosity(const Reader& r, const YAML::Node& sph) {
  if (!sph.IsDefined() || !sph["alpha"].IsDefined() || sph["viscosity"].IsDefined()) return;
  r.fail(sph["alpha"], "sph.alpha",
         "is the artificial viscosity's coefficient, and the default viscosity is laminar: add sph.viscosity: "
         "artificial (the paper's scheme), or remove alpha");
}

Case parse(const YAML::Node& root, Reader& r) {
  Case c;
  if (!root.IsMap()) r.fail(root, "", "the case file must be a mapping of keys (name, dp, time, ...)");
  r.check_keys(root, "", keys_under(""));
  c.name = r.require<std::string>(root, "", "name");
  if (c.name.empty() || c.name.find_first_of("/\\") != std::string::npos)
    r.fail(root["name"], "name", "must be a non-empty name without slashes");
  // dp matters for water and SPH walls; a DEM-only case may leave it out.
  const bool sph_case = root["fluid"].IsDefined() || root["walls"].IsDefined() || !root["dem"].IsDefined();
  c.dp = sph_case ? r.require<double>(root, "", "dp") : r.get(root, "", "dp", 0.01);
  if (!(c.dp > 0)) r.fail(root["dp"], "dp", "particle spacing must be positive");
  parse_section(r, root, "time", time_fields(), c.time);
  if (c.time.gauge_every == 0) c.time.gauge_every = c.time.output_every / 10;
  c.gravity = r.get(root, "", "gravity", c.gravity);
  if (!root["domain"].IsDefined()) r.fail(root, "domain", "is required");
  c.domain = parse_box(r, root["domain"], "domain", keys_under("domain"));
  parse_section(r, root, "sph", sph_fields(), c.sph);
  check_alpha_has_its_viscosity(r, root["sph"]);
  parse_periodic(r, root["domain"], c);
  parse_symmetry(r, root["domain"], c);
  for_each_item(r, root, "fluid", "expected a list of regions, like [{box: {min: [..], max: [..]}}]",
                [&](const YAML::Node& f, const std::string& path) { c.fluid.push_back(parse_fluid(r, f, path, c)); });
  std::size_t i = 0;
  for_each_item(r, root, "walls", "expected a list of walls", [&](const YAML::Node& w, const std::string& path) {
    c.walls.push_back(parse_wall(r, w, path, i++, c));
  });
  check_fluid_in_tanks(r, root, c);
  check_within_image_faces(r, root, c);
  for_each_item(
      r, root, "damping", "expected a list of zones, like [{face: xmax, length: 1.0}]",
      [&](const YAML::Node& z, const std::string& path) { c.damping.push_back(parse_damping(r, z, path, c)); });
  std::set<std::string> names;
  for_each_item(r, root, "gauges", "expected a list of gauges", [&](const YAML::Node& g, const std::string& path) {
    c.gauges.push_back(parse_gauge(r, g, path, c, names));
  });
  check_size(r, root, c);
  if (const auto d = root["dem"]; d.IsDefined()) parse_dem(r, d, c);
  parse_section(r, root, "coupling", coupling_fields(), c.coupling);
  if (const auto hz = root["hazard"]; hz.IsDefined()) parse_hazard(r, hz, c);
  check_whole(r, root, c);
  return c;
}

// yaml-cpp keeps both entries of a key given twice and lookups find the first, so a
// case with `dp: 0.01` and further down `dp: 0.02` would silently run at 0.01.
void reject_duplicate_keys(const YAML::Node& n, const std::string& file, const std::string& path) {
  if (n.IsMap()) {
    std::map<std::string, int> seen; // key -> line
    for (const auto& kv : n) {
      const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : std::string("?");
      const int line = kv.first.Mark().is_null() ? 0 : kv.first.Mark().line + 1;
      std::string full = path;
      if (!full.empty()) full += ".";
      full += key;
      const auto [it, fresh] = seen.emplace(key, line);
      if (!fresh)
        throw InputError(file, line, full,
                         "given twice, on line " + std::to_string(it->second) + " and on line " + std::to_string(line) +
                             "; keep one");
      reject_duplicate_keys(kv.second, file, full);
    }
  } else if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i)
      reject_duplicate_keys(n[i], file, (path.empty() ? "" : path + ".") + std::to_string(i));
  }
}

} // namespace

Case read_case_text(const std::string& text, const std::string& filename, const Overrides& overrides) {
  Reader r(filename);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(filename, e.mark.is_null() ? 0 : e.mark.line + 1, "", "malformed YAML: " + e.msg);
  } catch (const YAML::Exception& e) { throw InputError(filename, 0, "", std::string("malformed YAML: ") + e.what()); }
  if (!root.IsDefined() || root.IsNull()) throw InputError(filename, 0, "", "the case file is empty");
  reject_duplicate_keys(root, filename, "");
  for (const auto& o : overrides) apply_override(root, o, r);
  try {
    Case c = parse(root, r);
    c.source = filename;
    return c;
  } catch (const YAML::Exception& e) {
    throw InputError(filename, e.mark.is_null() ? 0 : e.mark.line + 1, "", std::string("invalid case: ") + e.what());
  }
}

Case read_case(const std::string& path, const Overrides& overrides) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(
        path, 0, "",
        "is a folder, not a case file (give the case's .yaml file; to continue a run in this folder: surge "
        "restart " +
            path + ")");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the case file");
  std::stringstream ss;
  ss << in.rdbuf();
  return read_case_text(ss.str(), path, overrides);
}

namespace {
void write_vec(YAML::Emitter& e, const Vec3d& v) {
  e << YAML::Flow << YAML::BeginSeq << v.x << v.y << v.z << YAML::EndSeq;
}
void write_box(YAML::Emitter& e, const Box& b) {
  e << YAML::Flow << YAML::BeginMap << YAML::Key << "min" << YAML::Value;
  write_vec(e, b.min);
  e << YAML::Key << "max" << YAML::Value;
  write_vec(e, b.max);
  e << YAML::EndMap;
}

// Writes the keys of one table declared in case_schema.cpp.
template <class S>
void write_fields(YAML::Emitter& e, const std::vector<Field<S>>& fields, const S& s, const char* skip = nullptr) {
  for (const auto& f : fields) {
    if (skip && f.key == std::string_view(skip)) continue;
    e << YAML::Key << f.key << YAML::Value;
    std::visit(
        [&](auto m) {
          if constexpr (std::is_same_v<std::decay_t<decltype(s.*m)>, Vec3d>)
            write_vec(e, s.*m);
          else
            e << s.*m;
        },
        f.member);
  }
}

template <class S>
void write_section(YAML::Emitter& e, const char* key, const std::vector<Field<S>>& fields, const S& s) {
  e << YAML::Key << key << YAML::Value << YAML::BeginMap;
  write_fields(e, fields, s);
  e << YAML::EndMap;
}

// A motion with the keys its law reads only (the reader refuses the others).
void write_motion(YAML::Emitter& e, const MotionSpec& m) {
  e << YAML::Key << "motion" << YAML::Value << YAML::BeginMap << YAML::Key << "law" << YAML::Value << m.law;
  std::vector<std::string> keys = law_keys(*motion::find_law(m.law));
  keys.emplace_back("start");
  std::vector<Field<MotionSpec>> fields;
  for (const auto& f : motion_fields())
    if (std::find(keys.begin(), keys.end(), f.key) != keys.end()) fields.push_back(f);
  write_fields(e, fields, m);
  if (m.pivot_given) {
    e << YAML::Key << "pivot" << YAML::Value;
    write_vec(e, m.pivot);
  }
  if (!m.csv.empty()) e << YAML::Key << "csv" << YAML::Value << m.csv_path;
  e << YAML::EndMap;
}

void write_walls(YAML::Emitter& e, const std::vector<WallSpec>& walls) {
  e << YAML::Key << "walls" << YAML::Value << YAML::BeginSeq;
  for (const auto& w : walls) {
    e << YAML::BeginMap << YAML::Key << "name" << YAML::Value << w.name;
    if (w.is_mesh) {
      e << YAML::Key << (w.terrain ? "terrain" : "mesh") << YAML::Value << w.mesh_path;
    } else {
      e << YAML::Key << "box" << YAML::Value;
      write_box(e, w.box);
      e << YAML::Key << "open" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (Face f : w.open) e << face_name(f);
      e << YAML::EndSeq;
    }
    write_fields(e, wall_fields(), w);
    if (w.motion.moves()) write_motion(e, w.motion);
    if (w.body.free) write_section(e, "body", body_fields(), w.body);
    e << YAML::EndMap;
  }
  e << YAML::EndSeq;
}

// Each gauge with the keys of its type only.
void write_gauge(YAML::Emitter& e, const GaugeSpec& g) {
  e << YAML::BeginMap << YAML::Key << "name" << YAML::Value << g.name << YAML::Key << "type" << YAML::Value
    << gauge_type(g.type).name;
  switch (g.type) {
  case GaugeType::Height:
    e << YAML::Key << "x" << YAML::Value << g.x << YAML::Key << "y" << YAML::Value << g.y << YAML::Key << "surface"
      << YAML::Value << g.surface;
    break;
  case GaugeType::Pressure:
  case GaugeType::Velocity:
    e << YAML::Key << "at" << YAML::Value;
    write_vec(e, g.at);
    break;
  case GaugeType::Force:
  case GaugeType::DemWall:
  case GaugeType::Body:
    e << YAML::Key << "wall" << YAML::Value << g.wall;
    break;
  case GaugeType::Sphere:
    e << YAML::Key << "sphere" << YAML::Value << g.sphere;
    break;
  }
  if (*gauge_type(g.type).components) e << YAML::Key << "component" << YAML::Value << g.component;
  if (g.type == GaugeType::DemWall) {
    e << YAML::Key << "about" << YAML::Value;
    write_vec(e, g.about);
  }
  e << YAML::EndMap;
}

void write_dem(YAML::Emitter& e, const DemConfig& d) {
  const auto material = [&](int k) { return d.materials[static_cast<std::size_t>(k)].name; };
  e << YAML::Key << "dem" << YAML::Value << YAML::BeginMap;
  write_fields(e, dem_fields(), d);
  e << YAML::Key << "materials" << YAML::Value << YAML::BeginSeq;
  for (const auto& m : d.materials) {
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << m.name;
    write_fields(e, material_fields(), m);
    e << YAML::Key << "rolling" << YAML::Value << YAML::Flow << YAML::BeginSeq << m.k_roll << m.k_roll_max
      << YAML::EndSeq << YAML::Key << "twisting" << YAML::Value << YAML::Flow << YAML::BeginSeq << m.k_twist
      << m.k_twist_max << YAML::EndSeq;
    if (m.bonded)
      e << YAML::Key << "bond" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "cn" << YAML::Value
        << m.bond_cn << YAML::Key << "cs" << YAML::Value << m.bond_cs << YAML::EndMap;
    e << YAML::EndMap;
  }
  e << YAML::EndSeq << YAML::Key << "walls" << YAML::Value << YAML::BeginSeq;
  for (const auto& w : d.walls) {
    e << YAML::BeginMap;
    write_fields(e, dem_wall_fields(), w);
    if (w.is_mesh) {
      e << YAML::Key << (w.terrain ? "terrain" : "mesh") << YAML::Value << w.mesh_path;
    } else {
      e << YAML::Key << "plane" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "point" << YAML::Value;
      write_vec(e, w.point);
      e << YAML::Key << "normal" << YAML::Value;
      write_vec(e, w.normal);
      e << YAML::EndMap;
    }
    e << YAML::Key << "material" << YAML::Value << material(w.material);
    if (w.motion.moves()) write_motion(e, w.motion);
    if (w.body.free) write_section(e, "body", body_fields(), w.body);
    if (!w.follows.empty()) e << YAML::Key << "follows" << YAML::Value << w.follows;
    e << YAML::EndMap;
  }
  e << YAML::EndSeq << YAML::Key << "packs" << YAML::Value << YAML::BeginSeq;
  for (const auto& pk : d.packs) {
    e << YAML::BeginMap;
    if (pk.from_csv) {
      e << YAML::Key << "csv" << YAML::Value << pk.csv;
    } else {
      if (!pk.bottom_path.empty()) {
        e << YAML::Key << "between" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "top" << YAML::Value
          << pk.top_path << YAML::Key << "bottom" << YAML::Value << pk.bottom_path << YAML::EndMap;
      } else if (pk.mesh_path.empty()) {
        e << YAML::Key << "box" << YAML::Value;
        write_box(e, pk.box);
      } else {
        e << YAML::Key << "mesh" << YAML::Value << pk.mesh_path;
      }
      e << YAML::Key << "radius" << YAML::Value << pk.radius;
    }
    e << YAML::Key << "material" << YAML::Value << material(pk.material);
    write_fields(e, pack_fields(), pk);
    e << YAML::EndMap;
  }
  e << YAML::EndSeq << YAML::EndMap;
}
} // namespace

std::string to_yaml(const Case& c) {
  YAML::Emitter e;
  e.SetDoublePrecision(12);
  e << YAML::BeginMap;
  e << YAML::Key << "name" << YAML::Value << c.name;
  e << YAML::Key << "dp" << YAML::Value << c.dp;
  write_section(e, "time", time_fields(), c.time);
  e << YAML::Key << "gravity" << YAML::Value;
  write_vec(e, c.gravity);
  e << YAML::Key << "domain" << YAML::Value;
  if (c.any_periodic() || c.any_symmetry()) {
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "min" << YAML::Value;
    write_vec(e, c.domain.min);
    e << YAML::Key << "max" << YAML::Value;
    write_vec(e, c.domain.max);
    const auto faces = [&](const char* key, auto listed) {
      e << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (int f = 0; f < 6; ++f)
        if (listed(f)) e << face_name(static_cast<Face>(f));
      e << YAML::EndSeq;
    };
    if (c.any_periodic()) faces("periodic", [&](int f) { return c.periodic[static_cast<std::size_t>(f / 2)]; });
    if (c.any_symmetry()) faces("symmetry", [&](int f) { return c.symmetry[static_cast<std::size_t>(f)]; });
    e << YAML::EndMap;
  } else {
    write_box(e, c.domain);
  }
  SphConfig sph = c.sph;
  sph.hmax = c.water_depth(); // the depth the speed of sound came from, whatever gave it
  write_section(e, "sph", sph_fields(), sph);
  e << YAML::Key << "fluid" << YAML::Value << YAML::BeginSeq;
  for (const auto& f : c.fluid) {
    e << YAML::BeginMap;
    if (f.reservoir) {
      e << YAML::Key << "reservoir" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "level"
        << YAML::Value << f.level << YAML::Key << "seed" << YAML::Value << YAML::Flow << YAML::BeginSeq << f.seed_x
        << f.seed_y << YAML::EndSeq << YAML::EndMap;
    } else if (f.given()) {
      e << YAML::Key << "particles" << YAML::Value << f.particles;
    } else {
      e << YAML::Key << "box" << YAML::Value;
      write_box(e, f.box);
    }
    write_fields(e, fluid_fields(), f, f.reservoir || f.given() ? "fill" : nullptr); // fill: a box's only
    e << YAML::EndMap;
  }
  e << YAML::EndSeq;
  write_walls(e, c.walls);
  if (!c.damping.empty()) {
    e << YAML::Key << "damping" << YAML::Value << YAML::BeginSeq;
    for (const auto& d : c.damping)
      e << YAML::Flow << YAML::BeginMap << YAML::Key << "face" << YAML::Value << face_name(d.face) << YAML::Key
        << "length" << YAML::Value << d.length << YAML::Key << "rate" << YAML::Value << d.rate << YAML::EndMap;
    e << YAML::EndSeq;
  }
  e << YAML::Key << "gauges" << YAML::Value << YAML::BeginSeq;
  for (const auto& g : c.gauges) write_gauge(e, g);
  e << YAML::EndSeq;
  if (c.dem.active()) write_dem(e, c.dem);
  write_section(e, "coupling", coupling_fields(), c.coupling);
  if (c.hazard.enabled) {
    e << YAML::Key << "hazard" << YAML::Value << YAML::BeginMap;
    write_fields(e, hazard_fields(), c.hazard);
    e << YAML::Key << "still_level" << YAML::Value << c.hazard.still_level << YAML::Key << "run_up" << YAML::Value
      << YAML::BeginSeq;
    for (const auto& l : c.hazard.run_up)
      e << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << l.name << YAML::Key << "from"
        << YAML::Value << YAML::Flow << YAML::BeginSeq << l.x0 << l.y0 << YAML::EndSeq << YAML::Key << "to"
        << YAML::Value << YAML::Flow << YAML::BeginSeq << l.x1 << l.y1 << YAML::EndSeq << YAML::EndMap;
    e << YAML::EndSeq << YAML::EndMap;
  }
  e << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

} // namespace surge::io
