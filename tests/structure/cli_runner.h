#pragma once
// Run the built `polycube` binary and capture its exit code, stdout and stderr (temporary files
// named by process id, so parallel test processes do not collide).

#include "support/scratch.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace polycube::test {

struct Cli {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

//! A fresh temporary folder for one test, removed when the test program ends (scratch.h).
inline std::filesystem::path temp_folder(const std::string& name) { return scratch_dir("pc_" + name); }

//! A path in single quotes for the shell (built by appending: GCC 12 warns falsely on "'" + s).
inline std::string quoted(const std::filesystem::path& p) {
  std::string s(1, '\'');
  s += p.string();
  s += '\'';
  return s;
}

//! Run `polycube <args>` (quote paths yourself).
inline Cli run_polycube(const std::string& args) {
  static int counter = 0;
  const std::string err_file = ::testing::TempDir() + "pc_err_" +
                               std::to_string(static_cast<long>(getpid())) + "_" +
                               std::to_string(counter++) + ".txt";
  const std::string cmd = std::string(POLYCUBE_CLI) + " " + args + " 2>" + err_file;
  Cli r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = read_file(err_file);
  std::remove(err_file.c_str());
  return r;
}

}  // namespace polycube::test
