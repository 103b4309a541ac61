// The corpus of issue 24 (heavy: `make test-heavy`): each defect alone and two combined, and
// three coarse solids, 24 meshes written as files. Each goes through `polycube run` with the
// default repairs, or exits 2 with one error line naming the remedy and then goes through with
// that remedy.
#include "cli/run_cli.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "support/shapes.h"
#include "support/scratch.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

namespace polycube {
namespace {

namespace fs = std::filesystem;

core::TriMesh box() { return test::make_box(10, 14, 8, 5); }

//! Without the triangles whose three vertices satisfy `cut` (unused vertices kept, as files
//! with holes have them).
core::TriMesh without(core::TriMesh m, const std::function<bool(const core::Vec3&)>& cut) {
  std::vector<core::Tri> kept;
  for (const core::Tri& t : m.cells)
    if (!(cut(m.points[t[0]]) && cut(m.points[t[1]]) && cut(m.points[t[2]]))) kept.push_back(t);
  m.cells = std::move(kept);
  return m;
}

core::TriMesh open_top(const core::TriMesh& m) {
  return without(m, [](const core::Vec3& p) { return p.z() == 8; });
}

//! Two triangles of the top face out: two holes.
core::TriMesh two_holes(core::TriMesh m) {
  std::vector<core::Tri> kept;
  int dropped = 0;
  for (const core::Tri& t : m.cells) {
    const bool top = m.points[t[0]].z() == 8 && m.points[t[1]].z() == 8 && m.points[t[2]].z() == 8;
    if (top && (dropped == 0 || dropped == 20) && dropped++ >= 0) continue;
    if (top) ++dropped;
    kept.push_back(t);
  }
  m.cells = std::move(kept);
  return m;
}

core::TriMesh with_degenerate_and_repeated(core::TriMesh m) {
  m.cells.push_back({0, 0, 1});
  m.cells.push_back(m.cells[3]);
  return m;
}

core::TriMesh cavity() {
  return test::join(test::make_box(10, 10, 10, 4), test::turned(test::make_box(3, 3, 3, 2, core::Vec3(3.5, 3.5, 3.5))));
}

core::TriMesh overlapping() {
  return test::join(test::make_box(10, 10, 10, 3), test::make_box(10, 10, 10, 3, core::Vec3(5, 5, 5)));
}

core::TriMesh pinched() {
  return test::join(test::make_box(10, 10, 10, 3), test::make_box(10, 10, 10, 3, core::Vec3(10, 10, 10)));
}

core::TriMesh debris() { return test::join(box(), test::make_box(1, 1, 1, 1, core::Vec3(30, 0, 0))); }

//! An OBJ text: BOM, comments, unknown statements, quads as polygons, negative indices and
//! v/vt/vn forms.
std::string quirky_obj() {
  const core::TriMesh b = test::make_box(10, 10, 10, 1);
  std::ostringstream s;
  s << "\xEF\xBB\xBF# exported\nmtllib box.mtl\no box\n";
  for (const core::Vec3& p : b.points) s << fmt::format("v {} {} {}\n", p.x(), p.y(), p.z());
  s << "vt 0 0\nvn 0 0 1\nusemtl grey\ns off\nc 1 2\n";
  // Each face's two triangles as one quad (the diagonal they share replaced by the path through
  // the second triangle's other vertex); the second half with negative (relative) indices.
  const int n = b.num_points();
  for (std::size_t t = 0; t + 1 < b.cells.size(); t += 2) {
    const core::Tri &a = b.cells[t], &c = b.cells[t + 1];
    std::vector<int> quad;
    for (int k = 0; k < 3; ++k) {
      const int from = a[k], to = a[(k + 1) % 3];
      quad.push_back(from);
      const bool diagonal = std::count(c.begin(), c.end(), from) && std::count(c.begin(), c.end(), to);
      if (diagonal)
        for (const int w : c)
          if (w != from && w != to) quad.push_back(w);
    }
    s << "f";
    for (const int v : quad) s << (t < 6 ? fmt::format(" {}/1/1", v + 1) : fmt::format(" {}", v - n));
    s << "\n";
  }
  return s.str();
}

struct Case {
  std::string name;
  std::function<void(const fs::path&)> write;
  std::string remedy;  //!< empty: goes through with the default repairs
};

std::function<void(const fs::path&)> mesh(core::TriMesh m) {
  return [m](const fs::path& p) { io::write_mesh(p, core::to_mesh_data(m)); };
}

std::vector<Case> corpus() {
  return {
      {"soup", mesh(test::soup_of(box())), ""},
      {"inward", mesh(test::turned(box())), ""},
      {"degenerate_repeated", mesh(with_degenerate_and_repeated(box())), ""},
      {"quirky_obj", [](const fs::path& p) { std::ofstream(p) << quirky_obj(); }, ""},
      {"cavity", mesh(cavity()), ""},
      {"debris", mesh(debris()), ""},  // two solids: mapped both (--largest-component drops one)
      {"open", mesh(open_top(box())), "--repair holes"},
      {"two_holes", mesh(two_holes(box())), "--repair holes"},
      {"overlapping", mesh(overlapping()), "--repair wrap --wrap-alpha 0.05"},
      {"pinched", mesh(pinched()), "--repair wrap --wrap-alpha 0.05"},
      {"tetrahedron", mesh(test::regular_tetrahedron()), ""},
      {"wedge", mesh(test::wedge()), ""},
      {"pyramid", mesh(test::pyramid()), ""},
      // two defects combined
      {"soup_inward", mesh(test::soup_of(test::turned(box()))), ""},
      {"soup_degenerate", mesh(test::soup_of(with_degenerate_and_repeated(box()))), ""},
      {"soup_cavity", mesh(test::soup_of(cavity())), ""},
      {"inward_degenerate", mesh(test::turned(with_degenerate_and_repeated(box()))), ""},
      {"soup_two_holes", mesh(test::soup_of(two_holes(box()))), "--repair holes"},
      {"inward_cavity", mesh(test::turned(cavity())), ""},
      {"open_inward", mesh(test::turned(open_top(box()))), "--repair holes"},
      {"soup_open", mesh(test::soup_of(open_top(box()))), "--repair holes"},
      {"soup_debris", mesh(test::soup_of(debris())), ""},
      {"inward_debris", mesh(test::turned(debris())), ""},
      {"soup_overlapping", mesh(test::soup_of(overlapping())), "--repair wrap --wrap-alpha 0.05"},
  };
}

TEST(RepairCorpus, EveryMeshGoesThroughOrIsRefusedWithTheRemedyThatWorks) {
  const fs::path dir = test::scratch_dir("repair_corpus");
  const std::vector<Case> cases = corpus();
  ASSERT_GE(cases.size(), 20u);
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path input = dir / (c.name + ".obj");
    c.write(input);
    const std::string run = fmt::format("run '{}' -o '{}' --hexes 300", input.string(), (dir / c.name).string());
    const auto first = test::run_cli(run);
    if (c.remedy.empty()) {
      EXPECT_EQ(first.exit_code, 0) << first.err;
      continue;
    }
    EXPECT_EQ(first.exit_code, 2) << first.err;
    const std::size_t error = first.err.find("polycube: error: ");
    ASSERT_NE(error, std::string::npos) << first.err;
    const std::string line = first.err.substr(error);
    EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1) << first.err;
    const std::string remedy = c.remedy.substr(0, c.remedy.find(" --wrap-alpha"));  // what the message names
    EXPECT_NE(line.find(remedy), std::string::npos) << first.err;
    const auto second = test::run_cli(run + " " + c.remedy);
    EXPECT_EQ(second.exit_code, 0) << second.err;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace polycube
