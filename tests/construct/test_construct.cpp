// Tests of construct/: tetrahedralization + refinement, graph-cut labeling, validity repair.
// Validity is judged by the independent validator in validator.h, not by labeling_check.
#include "construct/coarse_surface.h"
#include "construct/fine_surface.h"
#include "construct/construct.h"
#include "construct/label_surface.h"
#include "construct/labeling.h"
#include "construct/labeling_check.h"
#include "construct/labeling_repair.h"
#include "construct/orientation.h"
#include "construct/polycube_estimate.h"
#include "construct/tetrahedralize.h"
#include "core/errors.h"
#include "core/topology.h"
#include "io/mesh_io.h"

#include "construct/pipeline.h"
#include "construct/validator.h"
#include "support/fixtures.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <random>

#include <Eigen/Geometry>

#include <filesystem>
#include <set>
#include <map>

namespace polycube {
namespace {

namespace fs = std::filesystem;
using test::expect_valid;
using test::inverted_tets;
using test::run_model;
using test::run_pipeline;
using test::tet_volume;

// --- tetrahedralization ----------------------------------------------------------------------

TEST(Tetrahedralize, ACavityIsLeftEmptyAndItsShellStaysBoundary) {
  // A 4 x 4 x 4 box inside a 10 x 10 x 10 one (its shell facing the cavity), and a box nested
  // in the cavity: the island is filled again (depth 2), the cavity around it is not.
  core::TriMesh solid = test::make_box(10.0, 10.0, 10.0, 1);
  const auto add = [&solid](const core::TriMesh& shell, bool inward) {
    const int off = solid.num_points();
    for (const auto& p : shell.points) solid.points.push_back(p);
    for (const auto& t : shell.cells)
      solid.cells.push_back(inward ? core::Tri{t[0] + off, t[2] + off, t[1] + off}
                                   : core::Tri{t[0] + off, t[1] + off, t[2] + off});
  };
  add(test::make_box(4.0, 4.0, 4.0, 1, core::Vec3(3, 3, 3)), true);
  const auto hollow = construct::tetrahedralize(solid);
  EXPECT_NEAR(tet_volume(hollow.mesh), 1000.0 - 64.0, 1e-6);
  EXPECT_EQ(inverted_tets(hollow.mesh), 0);
  EXPECT_EQ(core::boundary(hollow.mesh).surface.num_cells(), 24);
  add(test::make_box(1.0, 1.0, 1.0, 1, core::Vec3(4.5, 4.5, 4.5)), false);
  const auto island = construct::tetrahedralize(solid);
  EXPECT_NEAR(tet_volume(island.mesh), 1000.0 - 64.0 + 1.0, 1e-6);
  EXPECT_EQ(core::boundary(island.mesh).surface.num_cells(), 36);
}

TEST(Tetrahedralize, CubeIsFilledKeepsItsSurfaceAndIsRefined) {
  const core::TriMesh cube = test::make_box(1.0, 1.0, 1.0, 1);
  const auto r = construct::tetrahedralize(cube);
  EXPECT_NEAR(tet_volume(r.mesh), 1.0, 1e-9);
  EXPECT_EQ(inverted_tets(r.mesh), 0);
  const auto bnd = core::boundary(r.mesh);
  EXPECT_EQ(bnd.surface.num_cells(), 12);
  const auto d = construct::boundary_defects(r.mesh);
  EXPECT_TRUE(d.ok()) << d.tets_with_several_boundary_facets << " "
                      << d.interior_edges_between_boundary_vertices;
  // The coarse cube needs the refinement: TetGen alone leaves tets with two boundary facets.
  construct::TetrahedralizeOptions raw;
  raw.refine = false;
  EXPECT_FALSE(construct::boundary_defects(construct::tetrahedralize(cube, raw).mesh).ok());
}

TEST(Tetrahedralize, MaxVolumeMakesMoreTets) {
  // A fine enough surface: with the surface kept (-Y), TetGen can only refine inside.
  const core::TriMesh cube = test::make_box(1.0, 1.0, 1.0, 8);
  construct::TetrahedralizeOptions coarse;
  construct::TetrahedralizeOptions fine;
  fine.max_volume = 0.0005;
  const auto a = construct::tetrahedralize(cube, coarse);
  const auto b = construct::tetrahedralize(cube, fine);
  EXPECT_GT(b.tetgen_tets, a.tetgen_tets);
  EXPECT_NEAR(tet_volume(b.mesh), 1.0, 1e-9);
  EXPECT_EQ(inverted_tets(b.mesh), 0);
  // Tets away from the surface respect the bound (the surface forbids Steiner points near it).
  int inner_over = 0;
  for (const auto& t : b.mesh.cells) {
    core::Vec3 c = core::Vec3::Zero();
    for (int k = 0; k < 4; ++k) c += b.mesh.points[t[k]] / 4;
    if (c.minCoeff() < 0.25 || c.maxCoeff() > 0.75) continue;
    core::TetMesh one;
    one.points = {b.mesh.points[t[0]], b.mesh.points[t[1]], b.mesh.points[t[2]],
                  b.mesh.points[t[3]]};
    one.cells = {{0, 1, 2, 3}};
    if (tet_volume(one) > 0.0005 * (1 + 1e-9)) ++inner_over;
  }
  EXPECT_EQ(inner_over, 0);
}

TEST(Tetrahedralize, RefineBoundaryOnAGivenTetMesh) {
  // A single tet: four boundary facets, all edges on the boundary.
  core::TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.cells = {{0, 1, 2, 3}};
  construct::prepare_tet_mesh(m);
  const auto stats = construct::refine_boundary(m);
  EXPECT_EQ(stats.split_tets, 1);
  EXPECT_TRUE(construct::boundary_defects(m).ok());
  EXPECT_NEAR(tet_volume(m), 1.0 / 6.0, 1e-12);
  EXPECT_EQ(inverted_tets(m), 0);
  EXPECT_EQ(core::boundary(m).surface.num_cells(), 4);
}

TEST(Tetrahedralize, InvertedInputTetMeshIsReoriented) {
  core::TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.cells = {{0, 2, 1, 3}};
  construct::prepare_tet_mesh(m);
  EXPECT_EQ(inverted_tets(m), 0);
}

TEST(Tetrahedralize, RefusesOpenSurface) {
  core::TriMesh cube = test::make_box(1.0, 1.0, 1.0, 2);
  const core::Tri removed = cube.cells.back();
  cube.cells.pop_back();
  try {
    construct::tetrahedralize(cube);
    FAIL() << "no exception";
  } catch (const core::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("open: 3 boundary edge(s) in 1 hole(s)"), std::string::npos) << what;
    EXPECT_NE(what.find("--repair holes"), std::string::npos) << what;  // the remedy
    // Where: the midpoint of one of the removed triangle's edges.
    bool named = false;
    for (int k = 0; k < 3; ++k) {
      const core::Vec3 mid = (cube.points[removed[k]] + cube.points[removed[(k + 1) % 3]]) / 2.0;
      named = named || what.find(fmt::format("the first at ({:.6g}, {:.6g}, {:.6g})", mid.x(),
                                             mid.y(), mid.z())) != std::string::npos;
    }
    EXPECT_TRUE(named) << what;
  }
}

TEST(Tetrahedralize, RefusesSheetsTouchingAtAVertexAndSaysWhere) {
  // Two unit boxes sharing only the corner (1, 1, 1).
  core::TriMesh a = test::make_box(1.0, 1.0, 1.0, 1);
  const core::TriMesh b = test::make_box(1.0, 1.0, 1.0, 1, core::Vec3(1, 1, 1));
  const int corner = static_cast<int>(
      std::find(a.points.begin(), a.points.end(), core::Vec3(1, 1, 1)) - a.points.begin());
  ASSERT_LT(corner, a.num_points());
  std::vector<int> index;
  for (const auto& p : b.points) {
    index.push_back(p == core::Vec3(1, 1, 1) ? corner : a.num_points());
    if (p != core::Vec3(1, 1, 1)) a.points.push_back(p);
  }
  for (const auto& t : b.cells) a.cells.push_back({index[t[0]], index[t[1]], index[t[2]]});
  try {
    construct::tetrahedralize(a);
    FAIL() << "no exception";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "1 vertex(es) where separate sheets touch, the first at (1, 1, 1)"),
              std::string::npos)
        << e.what();
  }
}

TEST(Tetrahedralize, RefusesNonManifoldEdge) {
  core::TriMesh cube = test::make_box(1.0, 1.0, 1.0, 1);
  // A fin of two triangles (front and back) hanging from the edge of vertices of cells[0].
  const int a = cube.cells[0][0];
  const int b = cube.cells[0][1];
  const int c = cube.num_points();
  cube.points.push_back((cube.points[a] + cube.points[b]) / 2 + core::Vec3(3, 3, 3));
  cube.cells.push_back({a, b, c});
  cube.cells.push_back({b, a, c});
  try {
    construct::tetrahedralize(cube);
    FAIL() << "no exception";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("manifold"), std::string::npos) << e.what();
  }
}

TEST(Tetrahedralize, RefusesSelfIntersectingSurface) {
  core::TriMesh a = test::make_box(1.0, 1.0, 1.0, 1);
  const core::TriMesh b = test::make_box(1.0, 1.0, 1.0, 1, core::Vec3(0.5, 0.4, 0.3));
  const int off = a.num_points();
  for (const auto& p : b.points) a.points.push_back(p);
  for (const auto& t : b.cells) a.cells.push_back({t[0] + off, t[1] + off, t[2] + off});
  try {
    construct::tetrahedralize(a);
    FAIL() << "no exception";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("self-intersect"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("near ("), std::string::npos) << e.what();  // where
    EXPECT_NE(std::string(e.what()).find("union"), std::string::npos) << e.what();    // the remedy
  }
}

TEST(Tetrahedralize, RefusesEmptySurface) {
  EXPECT_THROW(construct::tetrahedralize(core::TriMesh{}), core::InputError);
}

// --- fast polycube estimate ------------------------------------------------------------------

namespace {
std::vector<int> normal_labels(const core::TriMesh& m) {
  std::vector<int> labels;
  for (const auto& c : m.cells) {
    const core::Vec3 n = (m.points[c[1]] - m.points[c[0]]).cross(m.points[c[2]] - m.points[c[0]]);
    int best = 0;
    for (int l = 1; l < construct::kNumLabels; ++l)
      if (n.dot(construct::label_direction(l)) > n.dot(construct::label_direction(best))) best = l;
    labels.push_back(best);
  }
  return labels;
}
}  // namespace

TEST(PolycubeEstimate, BoxWithItsOwnLabelingIsReproduced) {
  // A box is already a polycube: the estimate keeps every edge vector, folds nothing.
  const core::TriMesh box = test::make_box(1.0, 2.0, 3.0, 3);
  const auto est = construct::estimate_polycube(box, normal_labels(box));
  EXPECT_TRUE(est.flipped.empty());
  EXPECT_NEAR(est.flipped_area, 0.0, 0.0);
  EXPECT_LT(est.edge_distortion, 1e-6);
  for (int v = 0; v < box.num_points(); ++v)
    EXPECT_LT((est.points[v] - box.points[v]).norm(), 1e-6);
}

TEST(PolycubeEstimate, TopLabeledDownwardsFolds) {
  // The top face labeled -Z stays on top (its plane is kept by the edge vectors) but faces
  // away from its label: exactly its triangles are folded, a sixth of the area of a cube.
  const core::TriMesh cube = test::make_box(1.0, 1.0, 1.0, 4);
  std::vector<int> labels = normal_labels(cube);
  int top = 0;
  for (int& l : labels)
    if (l == 4) {
      l = 5;
      ++top;
    }
  ASSERT_EQ(top, 2 * 4 * 4);
  const auto est = construct::estimate_polycube(cube, labels);
  EXPECT_EQ(static_cast<int>(est.flipped.size()), top);
  for (int t : est.flipped) EXPECT_EQ(labels[t], 5);
  EXPECT_NEAR(est.flipped_area, 1.0 / 6.0, 1e-9);
}

TEST(PolycubeEstimate, WrongLabelCountIsBadInput) {
  const core::TriMesh cube = test::make_box(1.0, 1.0, 1.0, 1);
  EXPECT_THROW(construct::estimate_polycube(cube, std::vector<int>(3, 0)), core::InputError);
}

// --- labeling --------------------------------------------------------------------------------

TEST(Labeling, CubeFacesGetTheirAxes) {
  const core::TriMesh cube = test::make_box(1.0, 2.0, 3.0, 3);
  const auto lab = construct::graph_cut_labeling(cube);
  for (int t = 0; t < cube.num_cells(); ++t) {
    const auto& c = cube.cells[t];
    const core::Vec3 n = (cube.points[c[1]] - cube.points[c[0]])
                             .cross(cube.points[c[2]] - cube.points[c[0]])
                             .normalized();
    EXPECT_NEAR(n.dot(construct::label_direction(lab.labels[t])), 1.0, 1e-12);
  }
  EXPECT_NEAR(construct::labeling_fidelity(cube, lab.labels), 0.0, 1e-12);
  const auto v = test::validate_labeling(cube, lab.labels);
  EXPECT_TRUE(v.valid());
  EXPECT_EQ(v.charts, 6);
  EXPECT_EQ(v.corners, 8);
}

TEST(Labeling, CompactnessReducesCharts) {
  // A sphere with radial noise: the best axis per triangle (no compactness) scatters small
  // charts along the diagonals; a strong compactness term leaves the cube's layout, exactly one
  // chart per label, the cube's 12 edges and 8 corners.
  core::TriMesh s = test::make_sphere(1.0, 24, 48);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.02, 0.02);
  for (auto& p : s.points) p *= 1.0 + noise(rng);
  construct::LabelingOptions none;
  none.compactness = 0.0;
  construct::LabelingOptions strong;
  strong.compactness = 3.0;
  const auto a = construct::check_labeling(s, construct::graph_cut_labeling(s, none).labels);
  const auto b = construct::check_labeling(s, construct::graph_cut_labeling(s, strong).labels);
  EXPECT_GT(a.layout.num_charts(), 6);
  ASSERT_EQ(b.layout.num_charts(), 6);
  std::vector<int> labels = b.layout.chart_label;
  std::sort(labels.begin(), labels.end());
  EXPECT_EQ(labels, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(b.layout.num_boundaries, 12);
  EXPECT_EQ(b.layout.corners.size(), 8u);
  EXPECT_GT(a.layout.num_boundaries, b.layout.num_boundaries);
}

TEST(Labeling, Deterministic) {
  const core::TriMesh s = test::make_torus(2.0, 0.7, 40, 20);
  const auto a = construct::graph_cut_labeling(s);
  const auto b = construct::graph_cut_labeling(s);
  EXPECT_EQ(a.labels, b.labels);
}

TEST(Labeling, BoundarySmoothingRemovesTeethOnly) {
  // A box labeled by its normals, with one triangle in the middle of the +Z face given -Y:
  // its three neighbours are +Z, so smoothing gives it +Z back and changes nothing else.
  const core::TriMesh box = test::make_box(1.0, 1.0, 1.0, 4);
  const auto lab = construct::graph_cut_labeling(box);
  std::vector<int> labels = lab.labels;
  // The +Z triangle whose centroid is nearest the middle of the face.
  int middle = -1;
  double best = 1e300;
  for (int t = 0; t < box.num_cells(); ++t) {
    if (labels[t] != 4) continue;
    const auto& c = box.cells[t];
    const core::Vec3 g = (box.points[c[0]] + box.points[c[1]] + box.points[c[2]]) / 3.0;
    const double d = (g - core::Vec3(0.5, 0.5, 1.0)).norm();
    if (d < best) best = d, middle = t;
  }
  ASSERT_GE(middle, 0);
  labels[middle] = 3;
  const int changed = construct::smooth_chart_boundaries(box, labels);
  EXPECT_EQ(changed, 1);
  EXPECT_EQ(labels, lab.labels);
  // Nothing to smooth on a clean labeling.
  std::vector<int> clean = lab.labels;
  EXPECT_EQ(construct::smooth_chart_boundaries(box, clean), 0);
  EXPECT_EQ(clean, lab.labels);
}

TEST(AxisRotation, RotatedBoxIsTurnedBackAndAlignedBoxKept) {
  const core::TriMesh box = test::make_box(1.0, 2.0, 3.0, 3);
  const construct::AxisRotation kept = construct::best_axis_rotation(box);
  EXPECT_TRUE(kept.rotation.isIdentity());
  EXPECT_NEAR(kept.energy_before, 1.0, 1e-12);
  core::TriMesh turned = box;
  const Eigen::Matrix3d Q =
      (Eigen::AngleAxisd(0.5, core::Vec3(1, 2, 3).normalized())).toRotationMatrix();
  for (core::Vec3& p : turned.points) p = Q * p;
  const construct::AxisRotation r = construct::best_axis_rotation(turned);
  EXPECT_GT(r.energy_before, 1.1);
  EXPECT_NEAR(r.energy_after, 1.0, 1e-4);
  // R Q maps each axis onto an axis (up to sign): a signed permutation matrix.
  const Eigen::Matrix3d P = r.rotation * Q;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(P.row(i).cwiseAbs().maxCoeff(), 1.0, 1e-3);
  EXPECT_NEAR(P.determinant(), 1.0, 1e-9);
}

TEST(LabelingCheck, FindsEachKindOfDefect) {
  const core::TriMesh cube = test::make_box(1.0, 1.0, 1.0, 4);
  auto labels = construct::graph_cut_labeling(cube).labels;
  ASSERT_TRUE(construct::check_labeling(cube, labels).valid());
  // One triangle of +Z relabelled -Z: an island chart with one neighbour, opposite to it.
  int t_top = -1;
  for (int t = 0; t < cube.num_cells() && t_top < 0; ++t)
    if (labels[t] == 4) t_top = t;
  auto bad = labels;
  bad[t_top] = 5;
  const auto chk = construct::check_labeling(cube, bad);
  EXPECT_FALSE(chk.valid());
  bool few = false, opposite = false;
  for (const auto& d : chk.defects) {
    few |= d.kind == construct::DefectKind::TooFewNeighbors;
    opposite |= d.kind == construct::DefectKind::OppositeNeighbors;
    EXPECT_FALSE(d.reason.empty());
  }
  EXPECT_TRUE(few);
  EXPECT_TRUE(opposite);
  // Both validators agree.
  EXPECT_FALSE(test::validate_labeling(cube, bad).valid());
  EXPECT_THROW(construct::check_labeling(cube, std::vector<int>(3, 0)), core::InputError);
}

// The top of a box labeled -Z is a valid labeling (six charts, four neighbours each, three
// axes at every corner) whose top chart faces away from its label: no polycube whose corners sit
// where the box's do has that face the right way round. It is found, and relabelled with the
// label it faces (+Z), which is the box's own labeling; a labeling without such a chart is left
// as it is, and the normals the labeling read (LabelingOptions::data_normals) are the ones judged.
TEST(LabelingRepair, AChartFacingAwayFromItsLabelIsRelabelled) {
  const core::TriMesh box = test::make_box(1.0, 2.0, 1.5, 3);
  const std::vector<int> own = normal_labels(box);
  std::vector<int> labels = own;
  for (int& l : labels)
    if (l == 4) l = 5;
  construct::RepairResult rep = construct::repair_labeling(box, labels);
  ASSERT_TRUE(rep.valid());
  ASSERT_EQ(rep.labels, labels);  // valid as it is: nothing for the repair to do
  const std::vector<int> backward = construct::backward_charts(box, rep.check.layout);
  ASSERT_EQ(backward.size(), 1u);
  EXPECT_EQ(rep.check.layout.chart_label[backward[0]], 5);
  const construct::RepairResult fixed = construct::relabel_backward_charts(box, rep, {});
  EXPECT_TRUE(fixed.valid());
  EXPECT_EQ(fixed.labels, own);
  EXPECT_TRUE(construct::backward_charts(box, fixed.check.layout).empty());

  const construct::RepairResult good = construct::repair_labeling(box, own);
  EXPECT_TRUE(construct::backward_charts(box, good.check.layout).empty());
  EXPECT_EQ(construct::relabel_backward_charts(box, good, {}).labels, own);

  // Judged by the normals the labeling read: with every normal turned upside down, the box's
  // own labeling has its +Z and -Z charts (and all others) facing away.
  std::vector<core::Vec3> flipped;
  for (const auto& t : box.cells)
    flipped.push_back(-(box.points[t[1]] - box.points[t[0]]).cross(box.points[t[2]] - box.points[t[0]]).normalized());
  EXPECT_EQ(construct::backward_charts(box, good.check.layout, flipped).size(), 6u);
}

TEST(LabelingCheck, CornerJoiningTwoEqualAxesIsADefect) {
  // A box whose +Z face's one quadrant is labelled +X: the corner of that quadrant joins
  // +X(patch), +Z, and the real +X side through a valence-4 or repeated-axis configuration.
  const core::TriMesh cube = test::make_box(1.0, 1.0, 1.0, 2);
  auto labels = construct::graph_cut_labeling(cube).labels;
  for (int t = 0; t < cube.num_cells(); ++t) {
    const auto& c = cube.cells[t];
    const core::Vec3 ctr = (cube.points[c[0]] + cube.points[c[1]] + cube.points[c[2]]) / 3;
    if (labels[t] == 4 && ctr.x() < 0.5 && ctr.y() < 0.5) labels[t] = 0;
  }
  const auto chk = construct::check_labeling(cube, labels);
  bool corner = false;
  for (const auto& d : chk.defects) corner |= d.kind == construct::DefectKind::InvalidCorner;
  EXPECT_TRUE(corner);
  EXPECT_FALSE(test::validate_labeling(cube, labels).valid());
}

// --- coarse surfaces: refined without moving them ---------------------------------------------

//! Whether p lies on one of the triangles of m (in its plane, inside it), to a relative tolerance.
bool on_surface(const core::TriMesh& m, const core::Vec3& p) {
  const double tol = 1e-12 * core::bounding_box(m.points).extent().norm();
  for (const core::Tri& t : m.cells) {
    const core::Vec3 a = m.points[t[0]], b = m.points[t[1]], c = m.points[t[2]];
    const core::Vec3 n = (b - a).cross(c - a);
    if (std::abs(n.normalized().dot(p - a)) > tol) continue;
    // Inside: p on the inner side of each edge (in the triangle's plane).
    const bool inside = n.dot((b - a).cross(p - a)) >= -tol * n.norm() &&
                        n.dot((c - b).cross(p - b)) >= -tol * n.norm() &&
                        n.dot((a - c).cross(p - c)) >= -tol * n.norm();
    if (inside) return true;
  }
  return false;
}

TEST(CoarseSurface, SplittingKeepsTheSurfaceWhereItWasAndHalvesEveryEdge) {
  const core::TriMesh w = test::wedge();
  const double longest = construct::longest_edge(w);
  EXPECT_DOUBLE_EQ(longest, std::sqrt(500.0));  // the base's diagonal
  construct::SurfaceRefinement done;
  const core::TriMesh fine = construct::subdivide_to(w, longest / 3.0, 1000000, done);
  EXPECT_EQ(done.levels, 2);  // halved twice: longest / 4 <= longest / 3
  EXPECT_EQ(done.triangles_before, 8);
  EXPECT_EQ(done.triangles_after, 128);
  EXPECT_EQ(fine.num_cells(), 128);
  EXPECT_DOUBLE_EQ(done.longest_edge_after, longest / 4.0);
  const auto report = core::analyze_surface(fine);
  EXPECT_EQ(report.boundary_edges, 0);
  EXPECT_TRUE(report.manifold);
  EXPECT_EQ(fine.points.size(), 2u + 128u / 2u);  // Euler: V = 2 + F / 2 on a sphere
  EXPECT_NEAR(core::signed_volume(fine), core::signed_volume(w), 1e-9 * core::signed_volume(w));
  for (const core::Vec3& p : fine.points) EXPECT_TRUE(on_surface(w, p)) << p.transpose();
  // The cap on triangles stops it: 32 fit under 100, 128 would not.
  const core::TriMesh capped = construct::subdivide_to(w, 1e-3, 100, done);
  EXPECT_EQ(done.levels, 1);
  EXPECT_EQ(capped.num_cells(), 32);
}

// --- fine surfaces: decimated within a tolerance ----------------------------------------------

TEST(FineSurface, ADenseSphereIsDecimatedWithinTheToleranceAndStaysAClosedOrientedSurface) {
  const core::TriMesh dense = test::sphere(5);  // 8,192 triangles on the unit sphere
  const double tolerance = 0.01;
  construct::SurfaceDecimation done;
  const std::optional<core::TriMesh> coarse = construct::decimate_surface(dense, 1000, tolerance, done);
  ASSERT_TRUE(coarse.has_value());
  EXPECT_TRUE(done.done());
  EXPECT_EQ(done.triangles_before, 8192);
  EXPECT_EQ(done.triangles_after, coarse->num_cells());
  EXPECT_LE(coarse->num_cells(), 1000);
  EXPECT_GE(coarse->num_cells(), 500);  // the tolerance allows 1,000 on a sphere; it stops at the count
  EXPECT_DOUBLE_EQ(done.tolerance, tolerance);
  const auto report = core::analyze_surface(*coarse);
  EXPECT_TRUE(report.closed);
  EXPECT_TRUE(report.manifold);
  EXPECT_TRUE(report.consistently_oriented);
  EXPECT_EQ(report.euler_characteristic, 2);
  EXPECT_EQ(report.degenerate_faces, 0);
  // The input lies between the unit sphere and its chords (sagitta < 1e-3 at this level), so a
  // point within the tolerance of it is within tolerance + sagitta of the unit sphere.
  for (const core::Vec3& p : coarse->points) EXPECT_NEAR(p.norm(), 1.0, tolerance + 1e-3) << p.transpose();
  EXPECT_GT(core::signed_volume(*coarse), 0.0);
  EXPECT_NEAR(core::signed_volume(*coarse), core::signed_volume(dense), 0.02 * core::signed_volume(dense));
  // Deterministic.
  construct::SurfaceDecimation again;
  const std::optional<core::TriMesh> twice = construct::decimate_surface(dense, 1000, tolerance, again);
  ASSERT_TRUE(twice.has_value());
  EXPECT_EQ(twice->points, coarse->points);
  EXPECT_EQ(twice->cells, coarse->cells);
}

TEST(FineSurface, ASurfaceWithinTheCountIsNotTouched) {
  construct::SurfaceDecimation done;
  EXPECT_FALSE(construct::decimate_surface(test::sphere(3), 512, 0.01, done).has_value());  // 512 triangles
  EXPECT_FALSE(construct::decimate_surface(test::sphere(3), 0, 0.01, done).has_value());    // 0: never
  EXPECT_FALSE(done.done());
}

TEST(FineSurface, TheToleranceKeepsABoxsCornersAndFlatFacesCollapse) {
  const core::TriMesh dense = test::make_box(10, 4, 2, 16);  // 3,072 triangles
  const double tolerance = 1e-3 * std::sqrt(120.0);
  construct::SurfaceDecimation done;
  const std::optional<core::TriMesh> coarse = construct::decimate_surface(dense, 100, tolerance, done);
  ASSERT_TRUE(coarse.has_value());
  EXPECT_LE(coarse->num_cells(), 100);
  const core::BoundingBox box = core::bounding_box(coarse->points);
  EXPECT_TRUE(box.min.isZero(tolerance)) << box.min.transpose();
  EXPECT_TRUE((box.max - core::Vec3(10, 4, 2)).isZero(tolerance)) << box.max.transpose();
  // Every vertex stays on the box's surface: within the tolerance of one of its faces.
  for (const core::Vec3& p : coarse->points) {
    const core::Vec3 inside = p.cwiseMin(core::Vec3(10, 4, 2) - p);  // distances to the 6 faces
    EXPECT_LE(inside.minCoeff(), tolerance) << p.transpose();
  }
  EXPECT_NEAR(core::signed_volume(*coarse), 80.0, 80.0 * 1e-2);
}

TEST(FineSurface, ConstructDecimatesADenseSurfaceAndCertifiesTheMapOfTheDecimatedSolid) {
  construct::ConstructOptions o;
  o.min_tets = 2000;
  o.max_triangles = 1000;
  o.decimate_to = 800;
  o.decimation_tolerance = 0.01;  // the default 1e-3 allows no collapse on so coarse a sphere
  const core::TriMesh dense = test::sphere(4);  // 2,048 triangles
  const construct::ConstructResult r = construct::construct_polycube(dense, o);
  EXPECT_TRUE(r.certificate.certified());
  ASSERT_TRUE(r.decimation.done());
  EXPECT_EQ(r.decimation.triangles_before, 2048);
  EXPECT_LE(r.decimation.triangles_after, 800);
  EXPECT_NEAR(r.decimation.tolerance, o.decimation_tolerance * core::bounding_box(dense.points).extent().norm(), 1e-12);
  EXPECT_GT(r.seconds.decimate, 0.0);
  // The map's model is the decimated solid, within the tolerance of the sphere.
  for (const core::Vec3& p : r.map.model_mesh().points)
    EXPECT_LE(p.norm(), 1.0 + r.decimation.tolerance) << p.transpose();
  // Not decimated when asked not to.
  o.max_triangles = 0;
  EXPECT_FALSE(construct::construct_polycube(dense, o).decimation.done());
}

TEST(CoarseSurface, AWedgeAndAPyramidConstructOnceRefinedAndNotOtherwise) {
  construct::ConstructOptions o;
  o.min_tets = 2000;  // enough for these shapes, and quick
  for (const auto& [name, shape] : {std::pair{"wedge", test::wedge()}, std::pair{"pyramid", test::pyramid()}}) {
    const construct::ConstructResult r = construct::construct_polycube(shape, o);
    EXPECT_TRUE(r.certificate.certified()) << name;
    EXPECT_EQ(r.coarse_refinement.triangles_before, shape.num_cells()) << name;
    EXPECT_GT(r.coarse_refinement.levels, 0) << name;
    EXPECT_LE(r.coarse_refinement.longest_edge_after,
              core::bounding_box(shape.points).extent().norm() / o.coarse_edge_ratio)
        << name;
    EXPECT_GE(r.charts, 6) << name;
    // The map's model is the solid: its volume is the shape's.
    EXPECT_NEAR(tet_volume(r.map.model_mesh()), core::signed_volume(shape),
                1e-9 * core::signed_volume(shape))
        << name;
  }
  o.coarse_edge_ratio = 0.0;  // never refine: no labeling of 6 or 8 triangles is valid
  EXPECT_THROW(construct::construct_polycube(test::pyramid(), o), construct::NoValidLabeling);
}

TEST(CoarseSurface, AThinSlabThatCannotBeLabeledSaysItsThicknessIsTheCause) {
  const core::TriMesh slab = test::make_box(1.0, 1.0, 1e-6, 1);
  ASSERT_EQ(slab.num_cells(), 12);
  try {
    construct::construct_polycube(slab, {});
    FAIL() << "a 1 x 1 x 1e-6 slab was labeled";
  } catch (const construct::NoValidLabeling& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("refined from 12 to"), std::string::npos) << what;
    EXPECT_NE(what.find("the solid is thin (mean thickness 2 volume / area = 1e-06"), std::string::npos) << what;
  }
  // A cube of 12 triangles is as coarse, but it labels as it is: nothing is refined.
  const construct::ConstructResult cube = construct::construct_polycube(test::make_box(1.0, 1.0, 1.0, 1), {});
  EXPECT_TRUE(cube.certificate.certified());
  EXPECT_EQ(cube.coarse_refinement.levels, 0);
}

// --- the whole pipeline on shapes built in code ---------------------------------------------

TEST(Pipeline, Cube) {
  const auto r = construct::tetrahedralize(test::make_box(2.0, 1.0, 1.0, 3));
  expect_valid(run_pipeline(r.mesh), "cube");
}

TEST(Pipeline, Sphere) {
  const auto r = construct::tetrahedralize(test::make_sphere(1.0, 20, 40));
  const auto p = run_pipeline(r.mesh);
  expect_valid(p, "sphere");
  EXPECT_GE(p.repair.check.layout.num_charts(), 6);
}

TEST(Pipeline, Torus) {
  const auto r = construct::tetrahedralize(test::make_torus(2.0, 0.7, 48, 24));
  const auto p = run_pipeline(r.mesh);
  expect_valid(p, "torus");
  EXPECT_EQ(core::analyze_surface(p.surface).genus, 1);
}

TEST(Pipeline, RepairFixesAPerturbedLabeling) {
  const core::TriMesh s = test::make_sphere(1.0, 16, 32);
  auto labels = construct::graph_cut_labeling(s).labels;
  // Scatter isolated wrong labels: islands, opposite neighbours, bad corners.
  for (int t = 0; t < s.num_cells(); t += 37) labels[t] = construct::opposite_label(labels[t]);
  ASSERT_FALSE(test::validate_labeling(s, labels).valid());
  const auto r = construct::repair_labeling(s, labels);
  EXPECT_GT(r.initial_defects, 0);
  EXPECT_TRUE(test::validate_labeling(s, r.labels).valid());
  EXPECT_TRUE(r.valid());
}

//! The corner tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), each face split into 4^levels.
core::TriMesh subdivided_corner_tetrahedron(int levels) {
  core::TriMesh m;
  m.points = {core::Vec3(0, 0, 0), core::Vec3(1, 0, 0), core::Vec3(0, 1, 0), core::Vec3(0, 0, 1)};
  m.cells = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> middle;
    const auto mid = [&](int a, int b) {
      const auto [it, fresh] = middle.emplace(std::minmax(a, b), m.num_points());
      if (fresh) m.points.push_back(0.5 * (m.points[a] + m.points[b]));
      return it->second;
    };
    std::vector<core::Tri> next;
    for (const core::Tri& t : m.cells) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.insert(next.end(), {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}});
    }
    m.cells = std::move(next);
  }
  return m;
}

std::set<int> labels_used(const std::vector<int>& labels) { return {labels.begin(), labels.end()}; }

// Every closed polycube has a chart facing each of the six directions, so the repair never
// takes a label's last triangles. Before it did, on a tetrahedron: its slanted face ties three
// axes, the moves that merged charts each removed a defect, and it ended with one chart of all
// 1,024 triangles (1 defect, no way back).
TEST(Pipeline, RepairNeverTakesADirectionsLastTriangles) {
  const core::TriMesh s = subdivided_corner_tetrahedron(4);
  const auto labeling = construct::graph_cut_labeling(s);
  const std::set<int> before = labels_used(labeling.labels);
  ASSERT_GE(before.size(), 4u);  // the three axis-aligned faces and the slanted one
  const auto r = construct::repair_labeling(s, labeling.labels);
  const std::set<int> after = labels_used(r.labels);
  for (const int l : before) EXPECT_TRUE(after.count(l)) << construct::label_name(l) << " was dropped";
  EXPECT_GE(construct::check_labeling(s, r.labels).layout.num_charts(), 4);
}

// --- shared models ----------------------------------------------------------------------------

const fs::path kData = POLYCUBE_DATA_DIR;

TEST(Models, Torus) { run_model(kData / "surface/torus.obj"); }
TEST(Models, ThreeHoles) { run_model(kData / "surface/3holes.obj"); }
TEST(Models, CubeMinusSphere) { run_model(kData / "surface/cube_minus_sphere.obj"); }
TEST(Models, Fandisk) { run_model(kData / "surface/fandisk.obj"); }
TEST(Models, TetB0) { run_model(kData / "tet/B0.mesh"); }
TEST(Models, TetSphere) { run_model(kData / "tet/sphere.mesh"); }
TEST(Models, TetCup) { run_model(kData / "tet/cup.mesh"); }

// A cut valid as it is stays: the looser one is not even looked at.
TEST(Pipeline, CutAndRepairKeepsAValidCut) {
  const core::TriMesh box = test::make_box(1.0, 2.0, 1.5, 3);
  const construct::CutAndRepair cr = construct::cut_and_repair(box, {}, {});
  EXPECT_EQ(cr.cut.compactness, construct::LabelingOptions{}.compactness);
  EXPECT_EQ(cr.cut.labels, construct::graph_cut_labeling(box, {}).labels);
  EXPECT_EQ(cr.repair.moves, 0);
  EXPECT_EQ(cr.repair.labels, cr.cut.labels);
}

// fandisk's compact cut leaves a chart with too few neighbours (a lip's underside, with two);
// the repair relabels all of it into the chart beside it, across a sharp crease, which the hex
// mesh then cuts across. The cut a little less compact is valid without a move: it is the one
// kept, and it is closer to the normals than the repaired compact cut.
TEST(Models, FandiskLabelingIsTheLooserCutValidWithoutRepair) {
  const construct::LabelSurfaceResult r = construct::label_surface(io::read_surface(kData / "surface/fandisk.obj"));
  const core::TriMesh& s = r.boundary.surface;
  ASSERT_TRUE(r.valid());
  EXPECT_EQ(r.initial_defects, 0);
  EXPECT_EQ(r.repair_moves, 0);
  const construct::CutAndRepair cr = construct::cut_and_repair(s, {}, {});
  EXPECT_EQ(cr.cut.compactness, construct::kLooserCut * construct::LabelingOptions{}.compactness);
  EXPECT_EQ(cr.cut.labels, r.labels);

  const construct::LabelingResult compact = construct::graph_cut_labeling(s, {});
  EXPECT_FALSE(construct::check_labeling(s, compact.labels).valid());
  const construct::RepairResult repaired = construct::repair_labeling(s, compact.labels);
  ASSERT_TRUE(repaired.valid());
  EXPECT_GT(repaired.moves, 0);
  EXPECT_LT(r.fidelity, construct::labeling_fidelity(s, repaired.labels));
}

}  // namespace
}  // namespace polycube
