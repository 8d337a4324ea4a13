// The gauge types a case names (gauges[].type), one row each: the case reader reads the
// type's name, its components and their default from here, the key reference prints
// them, and the run asks which side reads it. A new gauge type is a GaugeType, one row
// here, its location keys in the reader and its value in the sampler of its side.
#pragma once
#include "surge/core/case.hpp"

#include <cstddef>
#include <iterator>
#include <string>

namespace surge {

struct GaugeTypeInfo {
  const char* name;
  GaugeType type;
  // Read from the SPH particles (a DEM-only case has none of these); the others read the
  // spheres or a moving body.
  bool water;
  // The components it reads, space-separated, and the default ("": no component key).
  const char* components;
  const char* default_component;
  const char* help; // what each component is, for the reader's message
};

inline constexpr GaugeTypeInfo gauge_types[] = {
    {"height", GaugeType::Height, true, "", "", "the free surface's height (absolute z) on a vertical line"},
    {"pressure", GaugeType::Pressure, true, "", "", "the water's pressure at a point"},
    {"velocity", GaugeType::Velocity, true, "x y z mag", "mag", "a velocity gauge reads x, y, z or mag"},
    {"force", GaugeType::Force, true, "x y z mag", "x", "a force gauge reads x, y, z or mag"},
    {"sphere", GaugeType::Sphere, false, "x y z vx vy vz fx fy fz mx my mz", "z",
     "a sphere gauge reads x, y, z (centre), vx, vy, vz (velocity), fx, fy, fz (fluid force) or mx, my, mz (fluid "
     "moment about the centre)"},
    {"dem_wall", GaugeType::DemWall, false, "fx fy fz mx my mz", "fz",
     "a dem_wall gauge reads fx, fy, fz (force of the spheres on the wall) or mx, my, mz (moment about 'about')"},
    {"body", GaugeType::Body, false, "x y z vx vy vz fx fy fz mx my mz tilt", "z",
     "a body gauge reads x, y, z (pivot), vx, vy, vz (its velocity), fx, fy, fz (the load on it), mx, my, mz (its "
     "moment about the pivot) or tilt (degrees from upright)"},
};

// The row of a type (the table is in GaugeType's order).
[[nodiscard]] inline const GaugeTypeInfo& gauge_type(GaugeType t) { return gauge_types[static_cast<int>(t)]; }
static_assert(std::size(gauge_types) == static_cast<std::size_t>(GaugeType::Body) + 1, "a row per GaugeType");

// Whether `component` is one of the type's (whole words of its list).
[[nodiscard]] inline bool gauge_reads(const GaugeTypeInfo& g, const std::string& component) {
  const std::string list = std::string(" ") + g.components + " ";
  return !component.empty() && list.find(" " + component + " ") != std::string::npos;
}

// "height | pressure | ..." for the key reference; "height, pressure, ... or body" for messages.
[[nodiscard]] inline std::string gauge_type_list(const char* sep, const char* last) {
  std::string s;
  for (std::size_t k = 0; k < std::size(gauge_types); ++k)
    s += (k == 0 ? "" : (k + 1 == std::size(gauge_types) ? last : sep)) + std::string(gauge_types[k].name);
  return s;
}

} // namespace surge
