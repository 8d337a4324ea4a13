// Tables of numbers from text files (sphere lists, water given particle by particle).
#pragma once
#include "surge/core/error.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace surge {

// One row per line of numbers separated by commas, semicolons, tabs or spaces; '#' starts a
// comment, blank lines are skipped and a first line whose first word is no number is a header.
// Every row holds between `least` and `most` finite numbers. `columns` names them for the
// messages ("x, y, z, r"). Throws InputError naming the file and line; an empty table too.
struct NumberRow {
  std::vector<double> v;
  int line = 0;
};
inline std::vector<NumberRow> read_number_rows(const std::string& path, std::size_t least, std::size_t most,
                                               const std::string& columns, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open the " + what);
  std::vector<NumberRow> out;
  std::string line;
  int lineno = 0;
  const std::string expected =
      least == most ? "expected " + std::to_string(least) + " numbers: " + columns
                    : "expected " + std::to_string(least) + " to " + std::to_string(most) + " numbers: " + columns;
  while (std::getline(in, line)) {
    ++lineno;
    if (const auto h = line.find('#'); h != std::string::npos) line.resize(h);
    for (char& ch : line)
      if (ch == ',' || ch == ';' || ch == '\t' || ch == '\r') ch = ' ';
    std::istringstream ls(line);
    std::string first;
    if (!(ls >> first)) continue;
    char* after = nullptr;
    std::strtod(first.c_str(), &after);
    if (out.empty() && after == first.c_str()) continue; // a header: its first word is no number
    NumberRow row;
    row.line = lineno;
    std::istringstream all(line);
    std::string word;
    while (all >> word) {
      char* end = nullptr;
      const double x = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0' || !std::isfinite(x)) {
        std::string msg = "'";
        msg += word;
        msg += "' is not a finite number; ";
        msg += expected;
        throw InputError(path, lineno, "", msg);
      }
      row.v.push_back(x);
    }
    if (row.v.size() < least || row.v.size() > most) throw InputError(path, lineno, "", expected);
    out.push_back(std::move(row));
  }
  if (out.empty()) throw InputError(path, 0, "", "the " + what + " is empty");
  return out;
}

} // namespace surge
