#pragma once
// Shared helpers of the construct tests: run the pipeline, check it with the independent validator.
#include "construct/labeling.h"
#include "construct/labeling_repair.h"
#include "construct/tetrahedralize.h"
#include "core/topology.h"
#include "io/mesh_io.h"

#include "construct/validator.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <filesystem>
#include <string>

namespace polycube::test {

inline double tet_volume(const core::TetMesh& m) {
  double v = 0.0;
  for (const auto& t : m.cells) {
    const auto& p = m.points;
    v += (p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])) / 6.0;
  }
  return v;
}

inline int inverted_tets(const core::TetMesh& m) {
  int n = 0;
  for (const auto& t : m.cells) {
    const auto& p = m.points;
    if ((p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])) <= 0.0) ++n;
  }
  return n;
}

struct Pipeline {
  core::TetMesh mesh;
  core::TriMesh surface;
  std::vector<int> labels;
  construct::RepairResult repair;
};

inline Pipeline run_pipeline(const core::TetMesh& mesh) {
  Pipeline p;
  p.mesh = mesh;
  p.surface = core::boundary(mesh).surface;
  const auto lab = construct::graph_cut_labeling(p.surface);
  p.repair = construct::repair_labeling(p.surface, lab.labels);
  p.labels = p.repair.labels;
  return p;
}

// Every property the issue asks of the tet mesh and of the labeling, checked independently.
inline void expect_valid(const Pipeline& p, const std::string& what) {
  const auto d = construct::boundary_defects(p.mesh);
  EXPECT_EQ(d.tets_with_several_boundary_facets, 0) << what;
  EXPECT_EQ(d.interior_edges_between_boundary_vertices, 0) << what;
  EXPECT_EQ(inverted_tets(p.mesh), 0) << what;
  const auto v = validate_labeling(p.surface, p.labels);
  std::string problems;
  for (const auto& s : v.problems) problems += s + "; ";
  EXPECT_TRUE(v.valid()) << what << ": " << problems;
  // The library's verdict agrees with the independent one.
  EXPECT_EQ(p.repair.valid(), v.valid()) << what;
  EXPECT_EQ(p.repair.check.layout.num_charts(), v.charts) << what;
  EXPECT_EQ(static_cast<int>(p.repair.check.layout.corners.size()), v.corners) << what;
}

inline void run_model(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "missing " << path;
  core::TetMesh mesh;
  if (path.extension() == ".mesh") {
    mesh = core::tets_of(io::read_mesh(path));
    mesh.labels.clear();
    construct::prepare_tet_mesh(mesh);
    construct::refine_boundary(mesh);
  } else {
    mesh = construct::tetrahedralize(io::read_surface(path)).mesh;
  }
  expect_valid(run_pipeline(mesh), path.filename().string());
}


}  // namespace polycube::test
