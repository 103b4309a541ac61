#pragma once
// Checks of a whole construction (construct_polycube) shared by the model tests: the map is
// accepted by the independent certifier (certifier.h), its labeling by the independent labeling
// validator (validator.h), and its simplification is certified and keeps the structure.
#include "construct/construct.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "simplify/simplify.h"
#include "structure/structure.h"

#include "support/certifier.h"
#include "construct/validator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace polycube::test {

inline const std::filesystem::path kData = POLYCUBE_DATA_DIR;

inline void expect_certified(const construct::ConstructResult& r, const std::string& what) {
  const Verdict v = independent_check(r.map.tets, r.map.model, r.map.polycube, r.boundary, r.labels);
  EXPECT_TRUE(certified(v)) << what << ": bad model " << v.bad_model << ", bad polycube " << v.bad_polycube
                            << ", off plane " << v.off_plane << ", unlabeled " << v.unlabeled << ", wrong facing "
                            << v.wrong_facing;
  EXPECT_EQ(v.boundary_faces, static_cast<int>(r.boundary.size())) << what;
  core::TriMesh surface;
  surface.points = r.map.model;
  surface.cells = r.boundary;
  EXPECT_TRUE(validate_labeling(surface, r.labels).valid()) << what;
  EXPECT_GT(r.charts, 5) << what;
  EXPECT_GE(r.isometric_average, 1.0) << what;  // max(σ1, 1/σ3) >= 1 for every tet
}

//! Simplification (issue "polycube simplification") of a certified map: the output is certified by
//! the independent certifier with the construction's boundary labels, keeps the structure
//! (corners, edges, charts), has integer corners, and #D does not grow.
inline void expect_simplified(const construct::ConstructResult& r, const std::string& what) {
  const simplify::SimplifyResult s = simplify::simplify_map(r.map);
  ASSERT_TRUE(s.fit.certified) << what << ": " << (s.fit.failures.empty() ? "" : s.fit.failures.front());
  const auto& m = s.fit.map;
  ASSERT_EQ(m.tets, r.map.tets) << what;
  const Verdict v = independent_check(m.tets, m.model, m.polycube, r.boundary, r.labels);
  EXPECT_TRUE(certified(v)) << what << ": bad polycube " << v.bad_polycube << ", off plane " << v.off_plane
                            << ", wrong facing " << v.wrong_facing;
  const structure::PolycubeStructure before = structure::extract_structure(r.map);
  const structure::PolycubeStructure after = structure::extract_structure(m);
  EXPECT_EQ(after.corners.size(), before.corners.size()) << what;
  EXPECT_EQ(after.edges.size(), before.edges.size()) << what;
  EXPECT_EQ(after.charts.size(), before.charts.size()) << what;
  for (const auto& c : after.corners)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(c.position[a], std::round(c.position[a])) << what;
  EXPECT_LE(s.after.hex_domains, s.before.hex_domains) << what;
  EXPECT_LE(s.after.quad_domains, s.before.quad_domains) << what;
}

inline void construct_file(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "missing " << path;
  construct::ConstructResult r;
  if (path.extension() == ".mesh") {
    core::TetMesh mesh = core::tets_of(io::read_mesh(path));
    mesh.labels.clear();
    r = construct::construct_polycube(std::move(mesh));
  } else {
    r = construct::construct_polycube(io::read_surface(path));
  }
  expect_certified(r, path.filename().string());
  expect_simplified(r, path.filename().string());
}

}  // namespace polycube::test
