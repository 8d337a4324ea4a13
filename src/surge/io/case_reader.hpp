// Case file (YAML) -> typed Case. All parsing, validation and error messages live here.
#pragma once
#include "surge/core/case.hpp"

#include <string>
#include <vector>

namespace surge::io {

// "key.path=value" overrides from the command line, applied before validation.
using Overrides = std::vector<std::string>;

// Reads, overrides, validates. Throws InputError naming file, line and key.
Case read_case(const std::string& path, const Overrides& overrides = {});
// Same from text; `filename` is used in messages and to resolve mesh paths.
Case read_case_text(const std::string& text, const std::string& filename, const Overrides& overrides = {});
// The case as run, every default filled in, as YAML.
std::string to_yaml(const Case& c);

} // namespace surge::io
