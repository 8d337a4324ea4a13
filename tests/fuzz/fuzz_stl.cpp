// Any bytes given to the STL reader end in a mesh or an InputError, never a crash.
#include "surge/core/error.hpp"
#include "surge/geometry/stl_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const auto m = surge::geometry::parse_stl(bytes, "fuzz.stl");
    for (const auto& t : m.tris) (void)surge::geometry::closest_point(t, {0.1, 0.2, 0.3});
  } catch (const surge::InputError&) {}
  return 0;
}
