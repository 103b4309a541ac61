// Progress as a person sees it: on a terminal one bar per stage that only moves forward, with
// the elapsed time and an estimate; off a terminal no bar drawing in the log.
#include "run_cli.h"
#include "support/scratch.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace polycube::test {
namespace {

namespace fs = std::filesystem;

//! A folder of the test's own (ctest runs tests as parallel processes).
fs::path fresh_dir(const std::string& name) { return test::scratch_dir(name); }

std::string read_all(const fs::path& p) {
  std::string s;
  if (FILE* f = std::fopen(p.c_str(), "rb")) {
    char buf[4096];
    std::size_t n = 0;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) s.append(buf, n);
    std::fclose(f);
  }
  return s;
}

struct Bar {
  int percent = 0;
  int seconds = 0;
  bool estimate = false;
};

//! The bars drawn on the terminal, per stage, in order.
std::map<std::string, std::vector<Bar>> bars_of(const std::string& tty) {
  std::map<std::string, std::vector<Bar>> bars;
  const std::regex bar(R"(\x1b\[K(\S+) +\[[#.]{30}\] +(\d+)% (\d+) s(, ~\d+ s left)?)");
  for (auto it = std::sregex_iterator(tty.begin(), tty.end(), bar); it != std::sregex_iterator(); ++it)
    bars[(*it)[1]].push_back({std::stoi((*it)[2]), std::stoi((*it)[3]), (*it)[4].matched});
  return bars;
}

TEST(CliProgress, OnATerminalEachStageHasOneBarThatOnlyMovesForward) {
  if (std::system("command -v script >/dev/null 2>&1") != 0) GTEST_SKIP() << "no `script` to give the run a terminal";
  const fs::path dir = fresh_dir("pc_progress_tty");
  ASSERT_EQ(run_cli("sample l-bracket -o '" + (dir / "lb.obj").string() + "'").exit_code, 0);
  // `script` runs the command on a pseudo-terminal and copies what it draws to stdout.
  const std::string cmd = "script -qefc \"" + std::string(POLYCUBE_CLI) + " run '" + (dir / "lb.obj").string() +
                          "' -o '" + (dir / "out").string() + "' --hexes 1000\" /dev/null > '" +
                          (dir / "tty.txt").string() + "' 2>&1 </dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::map<std::string, std::vector<Bar>> bars = bars_of(read_all(dir / "tty.txt"));
  for (const char* stage : {"input", "construct", "simplify", "hexmesh", "optimize", "pad", "quality"}) {
    SCOPED_TRACE(stage);
    ASSERT_TRUE(bars.count(stage));
    const std::vector<Bar>& b = bars.at(stage);
    for (std::size_t i = 1; i < b.size(); ++i) {
      EXPECT_GE(b[i].percent, b[i - 1].percent);
      EXPECT_GE(b[i].seconds, b[i - 1].seconds);
    }
    EXPECT_EQ(b.back().percent, 100);
  }
  // The optimizer's bar moves through its rounds and says what is left.
  const std::vector<Bar>& opt = bars.at("optimize");
  int between = 0, estimates = 0;
  for (const Bar& b : opt) {
    between += b.percent > 0 && b.percent < 100;
    estimates += b.estimate;
  }
  EXPECT_GE(between, 5);
  EXPECT_GE(estimates, 1);
  // No other bar than the stages' (inner steps such as the untangling fill their stage's bar).
  EXPECT_EQ(bars.size(), 7u);

  // -q: no bar and no line at all, on a terminal too.
  const std::string quiet = "script -qefc \"" + std::string(POLYCUBE_CLI) + " -q run '" + (dir / "lb.obj").string() +
                            "' -o '" + (dir / "quiet").string() + "' --hexes 500 --no-simplify >/dev/null\" /dev/null > '" +
                            (dir / "quiet.txt").string() + "' 2>&1 </dev/null";
  ASSERT_EQ(std::system(quiet.c_str()), 0);
  EXPECT_EQ(read_all(dir / "quiet.txt"), "");
  fs::remove_all(dir);
}

TEST(CliProgress, OffATerminalTheLogHasNoBarDrawing) {
  const fs::path dir = fresh_dir("pc_progress_log");
  ASSERT_EQ(run_cli("sample l-bracket -o '" + (dir / "lb.obj").string() + "'").exit_code, 0);
  const CliResult r = run_cli("run '" + (dir / "lb.obj").string() + "' -o '" + (dir / "out").string() + "' --hexes 1000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos);
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos);
  // A line per stage as it starts; progress lines (at most one per 10 s) have the stage's name.
  EXPECT_NE(r.err.find("[5/7] optimize\n"), std::string::npos) << r.err;
  const std::regex line(R"(^      (\S+): (\d+)% \((\d+) s(, ~\d+ s left)?\)$)");
  std::istringstream in(r.err);
  std::map<std::string, int> last_seconds;
  for (std::string l; std::getline(in, l);) {
    if (l.rfind("      ", 0) != 0 || l.find("construct attempt") != std::string::npos) continue;
    std::smatch m;
    ASSERT_TRUE(std::regex_match(l, m, line)) << l;
    const int s = std::stoi(m[3]);
    if (last_seconds.count(m[1])) {
      EXPECT_GE(s - last_seconds[m[1]], 9) << l;  // 10 s apart, to the rounding
    }
    last_seconds[m[1]] = s;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace polycube::test
