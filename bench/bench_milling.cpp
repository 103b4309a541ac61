//! Benchmark of the checks of a part (issue 21, fabricate/milling.h, fabricate/printing.h): for
//! each surface, the time (median of 3) of the printing check on one base (overhanging area,
//! keels and tips), of the 3-axis check on one base, of the 4-axis check about one axis with 40
//! tool directions, and of the automatic axis (three 4-axis checks), with the fractions found.
//! Prints a text table, or JSON with --json.
//!
//! usage: bench_milling [--json] [SURFACE ...]
//!   Without surfaces: a bumpy torus of 100,000 triangles (its side facing the hole is hidden
//!   from tools orthogonal to its axis, so those triangles are tried from every direction) and a
//!   bumpy sphere of 131,072. A surface file is checked standing on -z, turning about z through
//!   its bounding box's centre.
#include "core/stopwatch.h"
#include "core/types.h"
#include "fabricate/milling.h"
#include "fabricate/printing.h"
#include "io/mesh_io.h"

#include "support/fixtures.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace polycube;
using core::Vec3;

constexpr int kRuns = 3;
constexpr int kDirections = 40;

struct Row {
  std::string model;
  int triangles = 0;
  double print_seconds = 0, three_axis_seconds = 0, four_axis_seconds = 0,
         choose_axis_seconds = 0;  // medians
  double support = 0;              // % overhanging area on -z
  int keels = 0, tips = 0;
  double unreachable_3am = 0, occluded_3am = 0, unreached_4am = 0, unreached_auto = 0;
};

template <class F>
double median_seconds(F&& f) {
  std::vector<double> t;
  for (int i = 0; i < kRuns; ++i) {
    const core::Stopwatch w;
    f();
    t.push_back(w.seconds());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

//! A torus (250 x 200 quads, 100,000 triangles) with bumps on its surface.
core::TriMesh bumpy_torus() {
  core::TriMesh m = test::split_quads(test::torus_quads(250, 200));
  for (Vec3& q : m.points)
    q *= 1.0 + 0.05 * std::sin(7 * q.x()) * std::cos(5 * q.y()) * std::cos(3 * q.z());
  return m;
}

//! The octahedron subdivided 7 times (131,072 triangles), radius bumped.
core::TriMesh bumpy_sphere() {
  core::TriMesh m = test::sphere(7);
  for (Vec3& q : m.points)
    q *= 1.0 + 0.15 * std::sin(6 * q.x()) * std::sin(6 * q.y()) * std::sin(6 * q.z());
  return m;
}

Row measure(const std::string& name, const core::TriMesh& m) {
  Row r;
  r.model = name;
  r.triangles = m.num_cells();
  Vec3 lo = m.points.front(), hi = m.points.front();
  for (const Vec3& p : m.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const fabricate::Axis axis{0.5 * (lo + hi), Vec3::UnitZ()};
  fabricate::Standing standing;
  fabricate::ThreeAxis three;
  fabricate::FourAxis four;
  r.print_seconds = median_seconds([&] { standing = fabricate::stand(m, -Vec3::UnitZ(), {}); });
  r.support = 100 * standing.support_fraction;
  r.keels = standing.keels;
  r.tips = standing.tips;
  fabricate::Axis automatic;
  r.three_axis_seconds =
      median_seconds([&] { three = fabricate::three_axis(m, -Vec3::UnitZ(), {}); });
  r.four_axis_seconds = median_seconds([&] { four = fabricate::four_axis(m, axis, kDirections); });
  r.choose_axis_seconds =
      median_seconds([&] { automatic = fabricate::choose_axis(m, kDirections); });
  r.unreachable_3am = 100 * three.unreachable;
  r.occluded_3am = 100 * three.occluded;
  r.unreached_4am = 100 * four.unreached;
  r.unreached_auto = 100 * fabricate::four_axis(m, automatic, kDirections).unreached;
  return r;
}

nlohmann::json to_json(const Row& r) {
  return {{"model", r.model},
          {"triangles", r.triangles},
          {"print_seconds", r.print_seconds},
          {"support_percent", r.support},
          {"keels", r.keels},
          {"tips", r.tips},
          {"three_axis_seconds", r.three_axis_seconds},
          {"four_axis_seconds", r.four_axis_seconds},
          {"choose_axis_seconds", r.choose_axis_seconds},
          {"unreachable_3am_percent", r.unreachable_3am},
          {"occluded_3am_percent", r.occluded_3am},
          {"unreached_4am_percent", r.unreached_4am},
          {"unreached_auto_axis_percent", r.unreached_auto}};
}

}  // namespace

int main(int argc, char** argv) {
  bool json = false;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json") {
      json = true;
    } else if (a.starts_with("-")) {
      std::cerr << "usage: bench_milling [--json] [SURFACE ...]\n";
      return 2;
    } else {
      files.push_back(a);
    }
  }
  std::vector<Row> rows;
  try {
    if (files.empty()) {
      rows.push_back(measure("bumpy torus", bumpy_torus()));
      rows.push_back(measure("bumpy sphere", bumpy_sphere()));
    }
    for (const std::string& f : files) rows.push_back(measure(f, io::read_surface(f)));
  } catch (const std::exception& e) {
    std::cerr << "bench_milling: " << e.what() << "\n";
    return 1;
  }
  if (json) {
    nlohmann::json out = nlohmann::json::array();
    for (const Row& r : rows) out.push_back(to_json(r));
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::printf("%-22s %9s %8s %8s %8s %8s %7s %6s %5s %7s %7s %7s %7s\n", "model", "triangles",
              "print s", "3-axis s", "4-axis s", "axis s", "support", "keels", "tips", "%3AM",
              "occl.%", "%4AM z", "%4AM au");
  for (const Row& r : rows)
    std::printf("%-22s %9d %8.3f %8.3f %8.3f %8.3f %7.2f %6d %5d %7.2f %7.2f %7.2f %7.2f\n",
                r.model.c_str(), r.triangles, r.print_seconds, r.three_axis_seconds,
                r.four_axis_seconds, r.choose_axis_seconds, r.support, r.keels, r.tips,
                r.unreachable_3am, r.occluded_3am, r.unreached_4am, r.unreached_auto);
  return 0;
}
