// `polycube structure`: counts of a valid map, exit code 2 and a message naming each failure
// for invalid maps.
#include "io/polycube_map_io.h"
#include "structure/analytic_maps.h"
#include "structure/cli_runner.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace polycube::test {
namespace {

namespace fs = std::filesystem;

struct MapFiles {
  fs::path model, polycube;
  [[nodiscard]] std::string args() const {
    std::string s = quoted(model);
    s += ' ';
    s += quoted(polycube);
    return s;
  }
};

MapFiles write(const fs::path& dir, const std::string& name, const core::PolycubeMap& m) {
  MapFiles f{dir / (name + "_model.mesh"), dir / (name + "_polycube.mesh")};
  io::write_polycube_map(f.model, f.polycube, m);
  return f;
}

int vertex_at(const core::PolycubeMap& m, const Vec3& p) {
  int best = 0;
  for (int v = 1; v < m.num_vertices(); ++v)
    if ((m.polycube[v] - p).norm() < (m.polycube[best] - p).norm()) best = v;
  return best;
}

TEST(StructureCli, CountsAndVtk) {
  const fs::path dir = temp_folder("structure_cli");
  const MapFiles f = write(dir, "l", l_shape(2).map);
  const Cli r = run_polycube("structure " + f.args() + " -o " + quoted(dir / "s.vtk") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["charts"], 8);
  EXPECT_EQ(j["edges"], 18);
  EXPECT_EQ(j["concave_edges"], 1);
  EXPECT_EQ(j["corners"], 12);
  EXPECT_EQ(j["faces_with_holes"], 0);
  const std::string vtk = read_file(dir / "s.vtk");
  EXPECT_EQ(vtk.rfind("# vtk DataFile Version 3.0", 0), 0u);
  const Cli t = run_polycube("structure " + f.args());
  EXPECT_EQ(t.exit_code, 0);
  EXPECT_NE(t.out.find("edges    18 (17 convex, 1 concave)"), std::string::npos) << t.out;
  fs::remove_all(dir);
}

TEST(StructureCli, InvalidMapsExitWithCode2AndNameTheFailure) {
  const fs::path dir = temp_folder("structure_cli_bad");
  struct Case {
    std::string name;
    core::PolycubeMap map;
    std::string expected;
  };
  std::vector<Case> cases;
  {
    auto m = l_shape(2).map;
    m.model[vertex_at(m, Vec3(0.5, 0.5, 0.5))] = Vec3(1.5, 0.5, 0.5);
    cases.push_back({"inverted", m, "inverted in model space"});
  }
  {
    auto m = l_shape(2).map;
    m.polycube[vertex_at(m, Vec3(0.5, 0.5, 0.5))] = m.polycube[vertex_at(m, Vec3(1.0, 0.5, 0.5))];
    cases.push_back({"flat", m, "flat (zero volume) in polycube space"});
  }
  {
    // The interior vertex pushed through a face of its star: tets invert in polycube space only.
    auto m = l_shape(2).map;
    m.polycube[vertex_at(m, Vec3(0.5, 0.5, 0.5))] = Vec3(1.5, 0.5, 0.5);
    cases.push_back({"inverted_polycube", m, "inverted in polycube space"});
  }
  {
    auto m = l_shape(2).map;
    m.model[vertex_at(m, Vec3(0.5, 0.5, 0.5))] = m.model[vertex_at(m, Vec3(1.0, 0.5, 0.5))];
    cases.push_back({"flat_model", m, "flat (zero volume) in model space"});
  }
  {
    auto m = l_shape(2).map;
    m.polycube[vertex_at(m, Vec3(0.5, 0.5, 1.0))].z() += 0.01;
    cases.push_back({"tilted", m, "not axis-aligned (tolerance"});
  }
  {
    auto m = l_shape(1).map;
    m.tets.push_back(m.tets[0]);
    cases.push_back({"open", m, "the polycube surface is not closed"});
  }
  for (const Case& c : cases) {
    const MapFiles f = write(dir, c.name, c.map);
    for (const char* cmd : {"structure ", "hexmesh "}) {
      std::string args(cmd);
      args += f.args();
      if (std::string(cmd) == "hexmesh ") {
        args += " -o ";
        args += quoted(dir / "out.mesh");
      }
      const Cli r = run_polycube(args);
      EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
      EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.name << ": " << r.err;
      EXPECT_FALSE(fs::exists(dir / "out.mesh"));
    }
  }
  // different connectivity between the two files
  auto m = l_shape(2).map;
  const MapFiles a = write(dir, "a", m);
  std::swap(m.tets[17][1], m.tets[17][2]);
  const MapFiles b = write(dir, "b", m);
  const Cli r = run_polycube("structure " + quoted(a.model) + " " + quoted(b.polycube));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("connectivity differs: tet 17"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace polycube::test
