// The case file's keys, each declared once: its place, type, default, unit, allowed
// values and one line of help. The reader parses and checks the keyed sections from these
// tables (time, sph, coupling, dem, each DEM material), to_yaml writes them back from
// them, and `surge keys` and docs/case_reference.md list every key from them. The items
// of the lists (fluid, walls, gauges, DEM walls and packs) take one shape or another: their
// optional keys are tables too (read, range-checked and documented from them); the keys
// that choose the shape or are required for one are read by hand and declared as
// reference entries here (the reader's allowed-key lists come from all of them).
#pragma once
#include "surge/core/case.hpp"

#include <limits>
#include <string>
#include <variant>
#include <vector>

namespace surge::io {

// The numbers a key may take: lo..hi, each end open or closed (infinite: no bound).
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  [[nodiscard]] bool holds(double v) const;
  // "must be positive", "must not be negative", "must be at least 1", "must lie in (0, 0.5]"
  [[nodiscard]] std::string message() const;
  // "> 0", ">= 0", "(0, 0.5]"; empty if any number is allowed
  [[nodiscard]] std::string text() const;
};
Range positive();
Range non_negative();
Range at_least(double lo);
Range between(double lo, bool lo_open, double hi, bool hi_open);

// One key of a section held in struct S.
template <class S>
struct Field {
  const char* key;
  std::variant<double S::*, int S::*, long S::*, bool S::*, std::string S::*, Vec3d S::*> member;
  const char* unit;                 // "" for none, "-" for a ratio
  Range range;                      // numbers
  std::vector<std::string> choices; // text keys with a fixed set of values
  const char* help;
};

const std::vector<Field<TimeConfig>>& time_fields();
const std::vector<Field<SphConfig>>& sph_fields();
const std::vector<Field<CouplingConfig>>& coupling_fields();
const std::vector<Field<DemConfig>>& dem_fields();
const std::vector<Field<HazardConfig>>& hazard_fields();
const std::vector<Field<DemMaterialSpec>>& material_fields();
// The optional keys of list items.
const std::vector<Field<FluidRegion>>& fluid_fields();
const std::vector<Field<WallSpec>>& wall_fields();
const std::vector<Field<MotionSpec>>& motion_fields();
const std::vector<Field<BodySpec>>& body_fields();
const std::vector<Field<GaugeSpec>>& gauge_fields();
const std::vector<Field<DemWallSpec>>& dem_wall_fields();
const std::vector<Field<DemPackSpec>>& pack_fields();

// A key as users read it: `path` with [] for a list's items ("walls[].box"), its type,
// default ("required", or empty where none applies), unit, allowed values, help.
struct KeyDoc {
  std::string path, type, def, unit, allowed, help;
};
// Every key, in the order of the reference.
const std::vector<KeyDoc>& case_keys();
// The keys allowed directly under `parent` ("" for the top level, "walls[]", "sph").
std::vector<std::string> keys_under(const std::string& parent);
// docs/case_reference.md.
std::string case_reference_markdown();
// `surge keys [PREFIX]`: the keys whose path starts with PREFIX, one per line.
std::string keys_text(const std::string& prefix);

} // namespace surge::io
