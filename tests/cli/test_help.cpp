// The help of every subcommand reads as words: choices by name, defaults and constraints in the
// description, no CLI11 internals (`{map->1,uniform->0}`, `{false}`) and no build path.
#include "run_cli.h"

#include <gtest/gtest.h>

#include <regex>
#include <sstream>
#include <string>
#include <vector>

using polycube::test::run_cli;

namespace {

//! The subcommand names listed by `polycube --help`.
std::vector<std::string> subcommands() {
  const auto r = run_cli("--help");
  std::istringstream in(r.out);
  std::vector<std::string> names;
  bool listing = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("Subcommands:", 0) == 0) {
      listing = true;
      continue;
    }
    if (listing && line.size() > 2 && line[0] == ' ' && line[2] != ' ') names.push_back(line.substr(2, line.find(' ', 2) - 2));
  }
  return names;
}

}  // namespace

TEST(CliHelp, EveryHelpSaysChoicesAndDefaultsInWords) {
  const std::vector<std::string> names = subcommands();
  ASSERT_GE(names.size(), 14u);
  for (const std::string& name : names) {
    for (const char* flag : {"--help", "--help-expert"}) {
      const auto r = run_cli(name + " " + flag);
      if (r.exit_code != 0) continue;  // no expert options in this subcommand
      SCOPED_TRACE(name + " " + flag);
      EXPECT_NE(r.out.find("Usage: polycube " + name + " "), std::string::npos) << r.out;
      EXPECT_FALSE(std::regex_search(r.out, std::regex(R"(\w->\d)"))) << r.out;  // CLI11's enum map
      EXPECT_EQ(r.out.find('{'), std::string::npos) << r.out;
      EXPECT_EQ(r.out.find("build/"), std::string::npos) << r.out;
      EXPECT_EQ(r.out.find("ENUM"), std::string::npos) << r.out;
    }
  }
  const auto run = run_cli("run --help").out;
  EXPECT_NE(run.find("--sizing uniform|map"), std::string::npos) << run;
  EXPECT_NE(run.find("(a positive number; default: 20000)"), std::string::npos) << run;
  EXPECT_NE(run.find("default: selective"), std::string::npos) << run;
  EXPECT_NE(run_cli("--help").out.find("Exit codes: 0 done"), std::string::npos);
}

TEST(CliHelp, ChoicesAreReadByNameInAnyCaseAndOthersRefused) {
  const auto bad = run_cli("run in.obj -o out --sizing bogus");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--sizing: must be one of uniform, map, got 'bogus'"), std::string::npos) << bad.err;
  // A valid choice passes parsing: the missing input then fails as bad input (exit 2), not usage.
  const std::string out = ::testing::TempDir() + "help_choice_" + std::to_string(getpid());
  EXPECT_EQ(run_cli("run /nonexistent/in.obj -o " + out + " --sizing MAP --padding Global").exit_code, 2);
}
