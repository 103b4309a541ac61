// The help of every subcommand reads as words: choices by name, defaults and constraints in the
// description, no CLI11 internals (`{map->1,uniform->0}`, `{false}`) and no build path.
#include "run_cli.h"
#include "support/scratch.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

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
  const std::string out = (polycube::test::scratch_dir("help_choice") / "out").string();
  EXPECT_EQ(run_cli("run /nonexistent/in.obj -o " + out + " --sizing MAP --padding Global").exit_code, 2);
}

// --save-config writes the command's settings (TOML), --config reads them back: the same run,
// with the same options in its report; the command line wins over the file.
TEST(CliConfig, SavedSettingsRunTheSameCommandAgain) {
  namespace fs = std::filesystem;
  const fs::path dir = polycube::test::scratch_dir("pc_config");
  const std::string config = (dir / "settings.toml").string(), out = (dir / "out").string();
  auto report_options = [&] {
    std::ifstream in(dir / "out" / "report.json");
    return nlohmann::json::parse(in)["options"];
  };
  const auto first = run_cli("--save-config '" + config + "' run '" + (dir / "missing.obj").string() + "' -o '" + out +
                             "' --hexes 1234 --padding none --no-simplify");
  EXPECT_EQ(first.exit_code, 2) << first.err;  // the input is missing: the settings are saved first
  ASSERT_TRUE(fs::exists(config));
  const nlohmann::json given = report_options();
  EXPECT_EQ(given["hexes"], "1234");
  EXPECT_EQ(given["no-simplify"], true);

  const auto again = run_cli("--config '" + config + "' run");
  EXPECT_EQ(again.exit_code, 2) << again.err;
  EXPECT_EQ(report_options(), given);

  const auto override = run_cli("--config '" + config + "' run --hexes 99");
  EXPECT_EQ(override.exit_code, 2) << override.err;
  EXPECT_EQ(report_options()["hexes"], "99");
  EXPECT_EQ(report_options()["padding"], "none");
  fs::remove_all(dir);
}

// --log FILE gets every message with its time, the info ones too (stderr shows warnings only).
TEST(CliLog, TheLogFileHoldsTheInfoMessagesWithTheirTime) {
  namespace fs = std::filesystem;
  const fs::path dir = polycube::test::scratch_dir("pc_log");
  const auto r = run_cli("--log '" + (dir / "run.log").string() + "' run '" + (dir / "missing.obj").string() + "' -o '" +
                         (dir / "out").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  std::ifstream in(dir / "run.log");
  std::string first;
  std::getline(in, first);
  EXPECT_TRUE(std::regex_search(first, std::regex(R"(^\d{4}-\d\d-\d\d \d\d:\d\d:\d\d\.\d{3} info: run: stage 1/\d+: input$)")))
      << first;
  EXPECT_EQ(r.err.find("info:"), std::string::npos) << r.err;
  fs::remove_all(dir);
}
