// Any bytes given to the case reader end in a Case or an InputError, never a crash.
#include "surge/core/error.hpp"
#include "surge/io/case_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const surge::Case c = surge::io::read_case_text(text, "fuzz.yaml");
    (void)surge::io::to_yaml(c);
  } catch (const surge::InputError&) {}
  return 0;
}
