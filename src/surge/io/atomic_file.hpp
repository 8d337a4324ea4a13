// Files are written to "<name>.tmp" and renamed, so a killed run never leaves a half-written file.
#pragma once
#include <string>
#include <string_view>

namespace surge::io {

void write_file_atomic(const std::string& path, std::string_view bytes);

} // namespace surge::io
