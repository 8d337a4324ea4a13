// Small cases for tests, built in memory.
#pragma once
#include "surge/io/case_reader.hpp"

#include <string>

namespace surge::test {

// A closed tank holding a water block; `shift` translates the whole case.
inline std::string tank_case(double dp, double shift = 0.0, const std::string& extra = "") {
  auto v = [&](double x, double y, double z) {
    return "[" + std::to_string(x + shift) + ", " + std::to_string(y + shift) + ", " + std::to_string(z + shift) + "]";
  };
  return "name: tank\n"
         "dp: " +
         std::to_string(dp) +
         "\n"
         "time: {end: 0.1, output_every: 0.05}\n"
         "domain: {min: " +
         v(0, 0, 0) + ", max: " + v(0.2, 0.1, 0.3) +
         "}\n"
         "fluid: [{box: {min: " +
         v(0, 0, 0) + ", max: " + v(0.08, 0.1, 0.16) +
         "}}]\n"
         "walls: [{name: tank, box: {min: " +
         v(0, 0, 0) + ", max: " + v(0.2, 0.1, 0.3) + "}, open: [zmax]}]\n" + extra;
}

} // namespace surge::test
