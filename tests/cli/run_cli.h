#pragma once
// Run the built `polycube` binary from tests and capture what it prints.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace polycube::test {

struct CliResult {
  int exit_code = -1;
  std::string out;  //!< stdout
  std::string err;  //!< stderr
};

//! Run `polycube <args>` (args are passed to the shell as given; quote paths yourself).
inline CliResult run_cli(const std::string& args) {
  static int counter = 0;
  const std::string err_file = ::testing::TempDir() + "pc_cli_err_" + std::to_string(getpid()) + "_" + std::to_string(counter++) + ".txt";
  const std::string cmd = std::string(POLYCUBE_CLI) + " " + args + " 2>" + err_file;
  CliResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (FILE* e = fopen(err_file.c_str(), "r")) {
    while ((n = fread(buf.data(), 1, buf.size(), e)) > 0) r.err.append(buf.data(), n);
    fclose(e);
  }
  std::remove(err_file.c_str());
  return r;
}

}  // namespace polycube::test
