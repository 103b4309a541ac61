#include "core/errors.h"

namespace polycube::core {

namespace {
std::string located(const std::string& file, long line, const std::string& what) {
  std::string s;
  if (!file.empty()) s += file + ":";
  if (line > 0) s += std::to_string(line) + ":";
  if (!s.empty()) s += " ";
  return s + what;
}
}  // namespace

InputError::InputError(const std::string& file, long line, const std::string& what)
    : Error(located(file, line, what)) {}

namespace detail {
void throw_internal(const char* cond, const char* file, int line, const std::string& msg) {
  throw InternalError(std::string(file) + ":" + std::to_string(line) + ": requirement `" + cond +
                      "` failed: " + msg);
}
}  // namespace detail

}  // namespace polycube::core
