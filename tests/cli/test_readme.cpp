// The README's quick start is what a newcomer types first: every line of it must run as written
// and leave the files the README then talks about. The commands are read from README.md itself,
// so a README edit that breaks them fails here rather than on a user's machine.
#include "support/scratch.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <regex>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

//! The repository's root: POLYCUBE_SOURCE_DIR when the build defines it, else the parent of
//! tests/ (POLYCUBE_TEST_DATA_DIR is "<repo>/tests/data").
fs::path source_dir() {
#ifdef POLYCUBE_SOURCE_DIR
  return fs::path(POLYCUBE_SOURCE_DIR);
#else
  return fs::path(POLYCUBE_TEST_DATA_DIR).parent_path().parent_path();
#endif
}

std::vector<std::string> readme_lines() {
  std::ifstream in(source_dir() / "README.md");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

//! The lines of the first ```sh block after the heading "## Quick start" (empty when missing).
std::vector<std::string> quick_start_commands(const std::vector<std::string>& lines) {
  std::vector<std::string> commands;
  bool in_section = false;
  bool in_block = false;
  for (const std::string& line : lines) {
    if (!in_section) {
      in_section = line == "## Quick start";
      continue;
    }
    if (!in_block) {
      if (line.rfind("## ", 0) == 0) break;  // the next section: no block in this one
      in_block = line == "```sh";
      continue;
    }
    if (line.rfind("```", 0) == 0) break;
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    commands.push_back(line.substr(first));
  }
  return commands;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST(CliReadme, FirstScreenSaysWhatAndHow) {
  // A newcomer reads about one screen: it has to say how to set up and how to run the chain.
  const std::vector<std::string> lines = readme_lines();
  ASSERT_FALSE(lines.empty()) << "cannot read " << source_dir() / "README.md";
  std::string first_screen;
  for (std::size_t i = 0; i < lines.size() && i < 40; ++i) first_screen += lines[i] + "\n";
  EXPECT_NE(first_screen.find("make demo"), std::string::npos) << first_screen;
  EXPECT_NE(first_screen.find("polycube run"), std::string::npos) << first_screen;
  // and show one picture of a result, a PNG committed with the project
  std::smatch picture;
  ASSERT_TRUE(std::regex_search(first_screen, picture, std::regex(R"(!\[[^\]]+\]\(([^)]+\.png)\))"))) << first_screen;
  std::ifstream png(source_dir() / picture[1].str(), std::ios::binary);
  std::string magic(8, '\0');
  ASSERT_TRUE(png.read(magic.data(), 8)) << picture[1];
  EXPECT_EQ(magic, std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST(CliReadme, QuickStartRunsAsWritten) {
  const std::vector<std::string> commands = quick_start_commands(readme_lines());
  ASSERT_EQ(commands.size(), 3u) << "the quick start should be one ```sh block of three commands";

  // A fresh folder, as a user's working directory would be; named by pid so that parallel
  // ctest runs do not share it.
  const fs::path dir = polycube::test::scratch_dir("pc_readme");

  const std::string word = "polycube ";
  for (const std::string& command : commands) {
    SCOPED_TRACE(command);
    // Every line starts with the command's name; it stands for the binary just built.
    ASSERT_EQ(command.rfind(word, 0), 0u) << "a quick-start line that is not a polycube command";
    const std::string shell = "cd '" + dir.string() + "' && '" + std::string(POLYCUBE_CLI) + "' " +
                              command.substr(word.size()) + " >quick_start.log 2>&1";
    const int status = std::system(shell.c_str());
    ASSERT_TRUE(WIFEXITED(status)) << shell;
    ASSERT_EQ(WEXITSTATUS(status), 0) << shell << "\n" << read_file(dir / "quick_start.log");
  }

  // The files the quick start and the outputs table then talk about.
  EXPECT_TRUE(fs::exists(dir / "flange.obj"));
  for (const char* name : {"construct/model.mesh", "construct/polycube.mesh", "simplify/model.mesh",
                           "simplify/polycube.mesh", "hex.mesh", "hex_optimized.mesh", "hex_quality.vtk",
                           "quad.vtk", "report.json"})
    EXPECT_TRUE(fs::exists(dir / "out" / name)) << name;
  const std::string report = read_file(dir / "out" / "report.json");
  EXPECT_NE(report.find("\"status\": \"ok\""), std::string::npos) << report.substr(0, 2000);
  // The last command's output: the optimized mesh has hexes and none inverted.
  const std::string info = read_file(dir / "quick_start.log");
  EXPECT_NE(info.find("hexahedra"), std::string::npos) << info;
  EXPECT_NE(info.find("0 inverted"), std::string::npos) << info;

  fs::remove_all(dir);
}
