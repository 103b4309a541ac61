// Our support figures against an outside slicer: PrusaSlicer slices each part of three samples
// (flange, l-bracket, ring) as we write it to print, standing on its chosen base, with support
// on at the same 45 degrees. A part we say needs no support must get no support extrusion, and
// over all the parts our support fractions must rank them as PrusaSlicer's support filament
// does (Spearman's rho >= 0.8). Skipped when prusa-slicer is not installed.
#include "cli/run_cli.h"
#include "fabricate/printing.h"
#include "io/mesh_io.h"

#include "../support/fixtures.h"
#include "support/scratch.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <regex>
#include <string>
#include <vector>

namespace polycube {
namespace {

namespace fs = std::filesystem;

bool have_prusa_slicer() { return std::system("command -v prusa-slicer >/dev/null 2>&1") == 0; }

//! Filament (mm along the feed) that a G-code file extrudes in its support sections (";TYPE:"
//! lines naming support material or its interface), in absolute or relative E mode.
double support_filament(const fs::path& gcode) {
  std::ifstream in(gcode);
  std::string line;
  bool support = false, relative = false;
  double e = 0.0, total = 0.0;
  static const std::regex e_word(R"(\sE(-?[0-9.]+))");
  while (std::getline(in, line)) {
    if (line.rfind(";TYPE:", 0) == 0) {
      support = line.find("Support") != std::string::npos;
    } else if (line.rfind("M83", 0) == 0) {
      relative = true;
    } else if (line.rfind("M82", 0) == 0) {
      relative = false;
    } else if (std::smatch m; (line.rfind("G1", 0) == 0 || line.rfind("G92", 0) == 0) &&
                              std::regex_search(line, m, e_word)) {
      const double value = std::stod(m[1]);
      if (line[1] == '9') {  // G92: the E axis renamed, nothing extruded
        e = value;
        continue;
      }
      const double step = relative ? value : value - e;
      if (!relative) e = value;
      if (support && step > 0) total += step;
    }
  }
  return total;
}

//! Support filament PrusaSlicer extrudes for an STL as it stands, support on at 45 degrees. Our
//! own data folder, so that no user profile changes the settings; a bed larger than any part.
double slice(const fs::path& stl, const fs::path& config) {
  const fs::path gcode = stl.string() + ".gcode";
  const std::string command = fmt::format(
      "prusa-slicer --datadir '{}' --export-gcode --support-material "
      "--support-material-threshold 45 --bed-shape 0x0,1000x0,1000x1000,0x1000 "
      "--max-print-height 1000 --center 500,500 -o '{}' '{}' > '{}.log' 2>&1",
      config.string(), gcode.string(), stl.string(), gcode.string());
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return support_filament(gcode);
}

//! Ranks 1..n, ties sharing their mean rank.
std::vector<double> ranks(const std::vector<double>& x) {
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return x[a] < x[b]; });
  std::vector<double> r(x.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && x[order[j + 1]] == x[order[i]]) ++j;
    for (std::size_t k = i; k <= j; ++k) r[order[k]] = (static_cast<double>(i + j) / 2) + 1;
    i = j + 1;
  }
  return r;
}

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
  const std::vector<double> ra = ranks(a), rb = ranks(b);
  const double n = static_cast<double>(a.size());
  const double ma = std::accumulate(ra.begin(), ra.end(), 0.0) / n;
  const double mb = std::accumulate(rb.begin(), rb.end(), 0.0) / n;
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    ab += (ra[i] - ma) * (rb[i] - mb);
    aa += (ra[i] - ma) * (ra[i] - ma);
    bb += (rb[i] - mb) * (rb[i] - mb);
  }
  return ab / std::sqrt(aa * bb);
}

TEST(SlicerSupport, TheKnownRanksHandleTies) {
  EXPECT_EQ(ranks({3.0, 1.0, 3.0, 0.0}), (std::vector<double>{3.5, 2.0, 3.5, 1.0}));
  EXPECT_NEAR(spearman({1, 2, 3, 4}, {10, 20, 30, 40}), 1.0, 1e-15);
  EXPECT_NEAR(spearman({1, 2, 3, 4}, {4, 3, 2, 1}), -1.0, 1e-15);
}

TEST(SlicerSupport, PrusaSlicerSupportsThePartsWeSayNeedItAndRanksThemAsWeDo) {
  if (!have_prusa_slicer()) GTEST_SKIP() << "prusa-slicer not installed";
  const fs::path dir = test::scratch_dir("slicer_support");
  fs::create_directories(dir / "config");
  std::vector<double> ours, slicer;
  for (const char* sample : {"flange", "l-bracket", "ring"}) {
    const fs::path shape = dir / (std::string(sample) + ".obj");
    const fs::path out = dir / sample;
    ASSERT_EQ(test::run_cli(fmt::format("sample {} -o {}", sample, shape.string())).exit_code, 0);
    const auto r =
        test::run_cli(fmt::format("-q fabricate {} -o {}", shape.string(), out.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(out / "parts" / "parts.json"));
    for (const auto& p : j["parts"]) {
      ASSERT_FALSE(p["print_file"].is_null()) << sample << " " << p["file"];
      const fs::path part = out / "parts" / p["print_file"].get<std::string>();
      const double filament = slice(part, dir / "config");
      const double percent = p["support_percent"].get<double>();
      if (!p["needs_support"].get<bool>()) {
        EXPECT_EQ(percent, 0.0);
        EXPECT_EQ(filament, 0.0) << sample << " " << p["file"];
      }
      ours.push_back(percent);
      slicer.push_back(filament);
    }
  }
  ASSERT_GE(ours.size(), 10u);
  EXPECT_GT(*std::max_element(slicer.begin(), slicer.end()), 0.0);  // some parts need support
  const double rho = spearman(ours, slicer);
  RecordProperty("spearman_rho", std::to_string(rho));
  EXPECT_GE(rho, 0.8);
}

TEST(SlicerSupport, PrusaSlicerSupportsAKeelThoughNoFaceOfItOverhangs) {
  if (!have_prusa_slicer()) GTEST_SKIP() << "prusa-slicer not installed";
  const fs::path dir = test::scratch_dir("slicer_keel");
  fs::create_directories(dir / "config");
  // 40 mm long, rising at 30 degrees from its end on the bed; its faces 60 degrees or more from
  // straight down.
  core::TriMesh keel = test::keel_prism(30);
  for (core::Vec3& p : keel.points) p *= 10.0;
  const fabricate::Standing s = fabricate::stand(keel, -core::Vec3::UnitZ(), {});
  EXPECT_EQ(s.support_fraction, 0.0);
  EXPECT_TRUE(s.needs_support());
  io::write_mesh((dir / "keel.stl").string(), core::to_mesh_data(keel));
  EXPECT_GT(slice(dir / "keel.stl", dir / "config"), 0.0);
}

}  // namespace
}  // namespace polycube
