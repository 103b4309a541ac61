// Validation of polycube maps: one invalid map per failure, each named in the message.
#include "core/errors.h"
#include "io/polycube_map_io.h"
#include "structure/analytic_maps.h"
#include "structure/validate.h"
#include "support/scratch.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace polycube::structure {
namespace {

using test::Vec3;

std::string message_of(const core::PolycubeMap& m) {
  try {
    validate_map(m);
  } catch (const core::InputError& e) {
    return e.what();
  }
  return {};
}

//! Index of the vertex nearest to p.
int vertex_at(const core::PolycubeMap& m, const Vec3& p) {
  int best = 0;
  for (int v = 1; v < m.num_vertices(); ++v)
    if ((m.polycube[v] - p).norm() < (m.polycube[best] - p).norm()) best = v;
  return best;
}

TEST(Validate, AnalyticMapsAreValid) {
  for (int r : {1, 2, 3}) {
    const MapDiagnosis d = diagnose_map(test::l_shape(r).map);
    EXPECT_TRUE(d.valid()) << (d.failures.empty() ? "" : d.failures[0]);
    EXPECT_EQ(d.boundary_triangles, 2 * 14 * r * r);  // two triangles per boundary grid square
    EXPECT_EQ(d.max_axis_deviation, 0.0);
  }
}

TEST(Validate, InvertedTetInModelSpace) {
  auto m = test::l_shape(2).map;
  const int v = vertex_at(m, Vec3(0.5, 0.5, 0.5));  // interior vertex
  m.model[v] = Vec3(1.5, 0.5, 0.5);                 // pushed through its neighbours
  const MapDiagnosis d = diagnose_map(m);
  EXPECT_GT(d.inverted_model, 0);
  EXPECT_EQ(d.inverted_polycube + d.flat_polycube, 0);
  const std::string msg = message_of(m);
  EXPECT_NE(msg.find("inverted in model space"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("polycube space"), std::string::npos) << msg;
}

TEST(Validate, FlatTetInPolycubeSpace) {
  auto m = test::l_shape(2).map;
  // Move an interior vertex onto the plane z = 0.5 of ... itself: flatten by collapsing it onto
  // a neighbour: every tet holding both becomes flat (two equal points).
  const int v = vertex_at(m, Vec3(0.5, 0.5, 0.5));
  const int w = vertex_at(m, Vec3(1.0, 0.5, 0.5));
  m.polycube[v] = m.polycube[w];
  const MapDiagnosis d = diagnose_map(m);
  EXPECT_GT(d.flat_polycube, 0);
  EXPECT_EQ(d.inverted_model + d.flat_model, 0);
  const std::string msg = message_of(m);
  EXPECT_NE(msg.find("flat (zero volume) in polycube space"), std::string::npos) << msg;
}

TEST(Validate, MirroredMeshIsNamedAsSuch) {
  auto m = test::l_shape(1).map;
  for (auto& t : m.tets) std::swap(t[0], t[1]);
  const std::string msg = message_of(m);
  EXPECT_NE(msg.find("vertex order is mirrored"), std::string::npos) << msg;
}

TEST(Validate, NonAxisAlignedBoundaryTriangle) {
  auto m = test::l_shape(2).map;
  const int v = vertex_at(m, Vec3(0.5, 0.5, 1.0));  // inside the top chart
  m.polycube[v].z() += 0.01;                        // lifted: its triangles tilt
  const MapDiagnosis d = diagnose_map(m);
  EXPECT_GT(d.non_axis_aligned, 0);
  EXPECT_EQ(d.inverted_polycube + d.flat_polycube, 0);
  const std::string msg = message_of(m);
  EXPECT_NE(msg.find("not axis-aligned (tolerance"), std::string::npos) << msg;
  EXPECT_NE(msg.find("along z"), std::string::npos) << msg;
  // the tolerance is an option: a loose one accepts the lift
  ValidateOptions loose;
  loose.axis_tolerance = 0.01;
  EXPECT_TRUE(diagnose_map(m, loose).valid());
}

TEST(Validate, OpenPolycubeSurface) {
  // A tet repeated: its boundary face is now shared twice (a hole in the surface) and its inner
  // faces three times: the tets do not close up into a solid.
  auto m = test::l_shape(1).map;
  m.tets.push_back(m.tets[0]);
  const MapDiagnosis d = diagnose_map(m);
  EXPECT_GT(d.open_edges, 0);
  EXPECT_GT(d.overshared_faces, 0);
  const std::string msg = message_of(m);
  EXPECT_NE(msg.find("the polycube surface is not closed"), std::string::npos) << msg;
}

TEST(Validate, NonManifoldPolycubeSurface) {
  // Two cubes sharing only an edge: every edge is matched but one has four triangles.
  const auto g = test::make_grid_map(
      test::uniform(0, 2, 2), test::uniform(0, 2, 2), test::uniform(0, 1, 1),
      [](const Vec3& c) { return (c.x() < 1) == (c.y() < 1); }, [](const Vec3& p) { return p; });
  const MapDiagnosis d = diagnose_map(g.map);
  EXPECT_GT(d.nonmanifold_edges, 0);
  EXPECT_NE(message_of(g.map).find("not manifold"), std::string::npos);
}

TEST(Validate, EveryFailureIsListed) {
  auto m = test::l_shape(2).map;
  m.model[vertex_at(m, Vec3(0.5, 0.5, 0.5))] = Vec3(1.5, 0.5, 0.5);
  m.polycube[vertex_at(m, Vec3(0.5, 0.5, 1.0))].z() += 0.01;
  const std::string msg = message_of(m);
  EXPECT_NE(msg.find("inverted in model space"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not axis-aligned"), std::string::npos) << msg;
}

TEST(Validate, BadIndicesAreInputErrors) {
  auto m = test::l_shape(1).map;
  m.tets[3][2] = 100000;
  EXPECT_THROW(diagnose_map(m), core::InputError);
  m = test::l_shape(1).map;
  m.model.pop_back();
  EXPECT_THROW(diagnose_map(m), core::InputError);
}

TEST(PolycubeMapIo, RoundTripAndConnectivityCheck) {
  const auto m =
      test::l_shape(2, [](const Vec3& p) { return Vec3(p.x() + 0.3 * p.z(), p.y(), p.z()); }).map;
  const std::filesystem::path dir = test::scratch_dir("pc_map_io");
  io::write_polycube_map(dir / "model.mesh", dir / "polycube.mesh", m);
  const core::PolycubeMap r = io::read_polycube_map(dir / "model.mesh", dir / "polycube.mesh");
  EXPECT_EQ(r.tets, m.tets);
  ASSERT_EQ(r.model.size(), m.model.size());
  for (std::size_t v = 0; v < m.model.size(); ++v) {
    EXPECT_EQ(r.model[v], m.model[v]);  // shortest exact decimal form: bit-exact
    EXPECT_EQ(r.polycube[v], m.polycube[v]);
  }
  // different connectivity: tet 17 reordered in the polycube file
  core::PolycubeMap other = m;
  std::swap(other.tets[17][1], other.tets[17][2]);
  io::write_polycube_map(dir / "model2.mesh", dir / "polycube2.mesh", other);
  try {
    io::read_polycube_map(dir / "model.mesh", dir / "polycube2.mesh");
    FAIL() << "connectivity difference not detected";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("connectivity differs: tet 17"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace polycube::structure
