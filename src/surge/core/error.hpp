// Error types: what the command line turns into exit codes (2: bad input, 3: run diverged).
#pragma once
#include <stdexcept>
#include <string>

namespace surge {

// A problem with the user's input, located by file, line and key.
class InputError : public std::runtime_error {
public:
  InputError(const std::string& file, int line, const std::string& key, const std::string& msg)
      : std::runtime_error(format(file, line, key, msg)), file_(file), line_(line), key_(key) {}
  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] int line() const { return line_; }
  [[nodiscard]] const std::string& key() const { return key_; }

private:
  static std::string format(const std::string& file, int line, const std::string& key, const std::string& msg) {
    std::string s;
    s.reserve(file.size() + key.size() + msg.size() + 16);
    s.append(file);
    if (line > 0) s.append(":").append(std::to_string(line));
    if (!key.empty()) s.append(": '").append(key).append("'");
    s.append(": ").append(msg);
    return s;
  }
  std::string file_;
  int line_;
  std::string key_;
};

// The simulation became unphysical (NaN, runaway particle loss, collapsing time step).
class DivergenceError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

} // namespace surge
