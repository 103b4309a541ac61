#pragma once
//! \file files.h
//! \brief Small helpers of the tests that run the `polycube` command: a written file read whole,
//! a path quoted for the shell.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace polycube::test {

//! The whole content of file `p` ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

//! `p` in single quotes, for a command line given to std::system.
inline std::string quoted(const std::filesystem::path& p) {
  std::string s(1, '\'');  // built piecewise: GCC 12 warns falsely on "'" + string
  s += p.string();
  s += '\'';
  return s;
}

}  // namespace polycube::test
