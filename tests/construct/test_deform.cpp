//! Tests of the untangling engine (solve/untangle.h, solve/sparse_solver.h), the polycube
//! deformation (construct/deform.h) and its certification (construct/certify.h), with an
//! independent certifier written here.
#include "construct/certify.h"
#include "construct/construct.h"
#include "construct/deform.h"
#include "construct/certifier.h"
#include "construct/labeling_check.h"
#include "construct/labeling_repair.h"
#include "construct/predeform.h"
#include "construct/tetrahedralize.h"
#include "core/errors.h"
#include "core/fixtures.h"
#include "core/polycube_map.h"
#include "core/topology.h"
#include "quality/distortion.h"
#include "solve/sparse_solver.h"
#include "solve/untangle.h"

#include <Eigen/Geometry>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

namespace polycube {
namespace {

using core::Vec3;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

using test::independent_check;
using test::Verdict;

// --- fixtures ---------------------------------------------------------------------------------

//! Closed triangulated surface of the cube [0,s]^3 with n x n squares per face (outward).
core::TriMesh cube_surface(int n, double s = 1.0) {
  core::TriMesh m;
  std::map<std::array<long, 3>, int> ids;
  auto vid = [&](const Vec3& p) {
    const std::array<long, 3> k{std::lround(p.x() * n / s), std::lround(p.y() * n / s), std::lround(p.z() * n / s)};
    auto it = ids.find(k);
    if (it != ids.end()) return it->second;
    m.points.push_back(p);
    return ids[k] = m.num_points() - 1;
  };
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const int u = (a + 1) % 3, w = (a + 2) % 3;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto pt = [&](int di, int dj) {
            Vec3 p;
            p[a] = side * s;
            p[u] = (i + di) * s / n;
            p[w] = (j + dj) * s / n;
            return vid(p);
          };
          const int p00 = pt(0, 0), p10 = pt(1, 0), p11 = pt(1, 1), p01 = pt(0, 1);
          if (side == 1) {  // normal +a = u x w: counter-clockwise in (u, w)
            m.cells.push_back({p00, p10, p11});
            m.cells.push_back({p00, p11, p01});
          } else {
            m.cells.push_back({p00, p11, p10});
            m.cells.push_back({p00, p01, p11});
          }
        }
    }
  return m;
}

//! Boundary triangles (volume indices, outward) of a tet mesh and labels from their normals.
void normal_labels(const core::TetMesh& mesh, std::vector<core::Tri>& tris, std::vector<int>& labels) {
  const core::TetBoundary b = core::boundary(mesh);
  tris.clear();
  labels.clear();
  for (const auto& s : b.surface.cells) {
    const core::Tri t{b.vertex_map[s[0]], b.vertex_map[s[1]], b.vertex_map[s[2]]};
    tris.push_back(t);
    const Vec3 n = (mesh.points[t[1]] - mesh.points[t[0]]).cross(mesh.points[t[2]] - mesh.points[t[0]]);
    labels.push_back(core::dominant_axis_label(n));
  }
}

// --- element energy and sparse solver ---------------------------------------------------------

TEST(EllipticEnergy, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.5, 1.5);
  for (int trial = 0; trial < 6; ++trial) {
    Eigen::Matrix3d J;
    for (int i = 0; i < 9; ++i) J(i / 3, i % 3) = U(rng);
    if (trial == 0) J = Eigen::Matrix3d::Identity();
    const double eps = trial % 2 ? 0.3 : 1e-2;
    const auto e = solve::elliptic_energy(J, eps, 1.0);
    const double h = 1e-6;
    for (int i = 0; i < 9; ++i) {
      Eigen::Matrix3d Jp = J, Jm = J;
      Jp(i / 3, i % 3) += h;
      Jm(i / 3, i % 3) -= h;
      const auto ep = solve::elliptic_energy(Jp, eps, 1.0);
      const auto em = solve::elliptic_energy(Jm, eps, 1.0);
      const double scale = 1.0 + std::abs(e.gradient[i]);
      EXPECT_NEAR((ep.value - em.value) / (2 * h), e.gradient[i], 1e-5 * scale) << "trial " << trial;
      for (int j = 0; j < 9; ++j)
        EXPECT_NEAR((ep.gradient[j] - em.gradient[j]) / (2 * h), e.hessian(j, i), 1e-4 * (1.0 + e.hessian.norm()))
            << "trial " << trial << " (" << j << "," << i << ")";
    }
  }
  // At the identity the energy is minimal over the shape term: value = 1 + λ·2/χ(1,ε) ~ 3.
  const auto id = solve::elliptic_energy(Eigen::Matrix3d::Identity(), 1e-9, 1.0);
  EXPECT_NEAR(id.value, 3.0, 1e-9);
  EXPECT_LT(id.gradient.norm(), 1e-9);
}

TEST(SparseSpdSolver, SolvesAndRejectsIndefinite) {
  const int n = 50;
  std::vector<Eigen::Triplet<double>> trip;
  for (int i = 0; i < n; ++i) {
    trip.emplace_back(i, i, 4.0);
    if (i + 1 < n) {
      trip.emplace_back(i, i + 1, -1.0);
      trip.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  A.makeCompressed();
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  solve::SparseSpdSolver s;
  s.analyze(A);
  ASSERT_TRUE(s.factorize(A));
  const Eigen::VectorXd x = s.solve(b);
  EXPECT_LT((A * x - b).norm(), 1e-10 * b.norm());
  // Refactorize with new values on the same pattern.
  Eigen::SparseMatrix<double> A2 = A * 2.0;
  ASSERT_TRUE(s.factorize(A2));
  EXPECT_LT((A2 * s.solve(b) - b).norm(), 1e-10 * b.norm());
  // Indefinite: refused, and solving then throws.
  Eigen::SparseMatrix<double> B = A;
  B.coeffRef(3, 3) = -10.0;
  EXPECT_FALSE(s.factorize(B));
  EXPECT_THROW((void)s.solve(b), core::SolverError);
}

// --- untangling -------------------------------------------------------------------------------

struct FoldedGrid {
  core::TetMesh mesh;
  std::vector<int> var;  // 3#V
  int nvar = 0;
};

//! 3x3x3 grid split into tets; boundary vertices fixed; the interior vertex (1,1,1) pushed
//! through the far side of its neighbourhood so that tets around it are inverted.
FoldedGrid folded_grid() {
  FoldedGrid g;
  g.mesh = test::tetrahedralize(test::hex_grid(3, 3, 3));
  const int nv = g.mesh.num_points();
  g.var.assign(3 * nv, -1);
  for (int v = 0; v < nv; ++v) {
    const Vec3& p = g.mesh.points[v];
    const bool bnd = (p.array() == 0.0).any() || (p.array() == 3.0).any();
    if (!bnd)
      for (int d = 0; d < 3; ++d) g.var[3 * v + d] = g.nvar++;
  }
  g.mesh.points[1 + 4 * (1 + 4 * 1)] = Vec3(2.7, 2.6, 2.8);  // vertex (1,1,1) beyond (2,2,2)
  return g;
}

int inverted_count(const core::TetMesh& m, const std::vector<Vec3>& p) {
  int n = 0;
  for (const auto& t : m.cells)
    n += (p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])) <= 0;
  return n;
}

TEST(Untangle, FoldedVertexBecomesValidAndFixedCoordinatesStay) {
  FoldedGrid g = folded_grid();
  const core::TetMesh ref = test::tetrahedralize(test::hex_grid(3, 3, 3));
  ASSERT_GT(inverted_count(g.mesh, g.mesh.points), 0);
  const Eigen::VectorXd x_init = solve::flatten(g.mesh.points);
  const solve::LinearReduction R = solve::index_reduction(g.var, g.nvar, x_init);
  Eigen::VectorXd y(g.nvar);
  for (int i = 0; i < 3 * g.mesh.num_points(); ++i)
    if (g.var[i] >= 0) y[g.var[i]] = x_init[i];
  const solve::TetElements el = solve::reference_elements(ref.points, ref.cells);
  const solve::UntangleResult r = solve::untangle(el, R, y, {});
  EXPECT_GT(r.inverted_before, 0);
  EXPECT_TRUE(r.untangled);
  EXPECT_EQ(r.inverted_after, 0);
  EXPECT_GT(r.min_det, 0.0);
  const Eigen::VectorXd x = R.apply(y);
  const std::vector<Vec3> p = solve::unflatten(x);
  EXPECT_EQ(inverted_count(g.mesh, p), 0);
  for (int i = 0; i < x.size(); ++i) {
    if (g.var[i] < 0) {
      EXPECT_EQ(x[i], x_init[i]) << "fixed coordinate " << i << " moved";
    }
  }
  // The optimum of this fixture is the undistorted grid: the vertices come back close to it.
  double err = 0;
  for (int v = 0; v < ref.num_points(); ++v) err = std::max(err, (p[v] - ref.points[v]).norm());
  EXPECT_LT(err, 0.05);
}

TEST(Untangle, SharedVariableConstraintIsExact) {
  // All interior vertices of the grid with z = 1 share one z variable (a "chart" constraint),
  // and they start tangled.
  FoldedGrid g = folded_grid();
  const core::TetMesh ref = test::tetrahedralize(test::hex_grid(3, 3, 3));
  const int nv = g.mesh.num_points();
  const int shared = g.nvar++;
  std::vector<int> members;
  for (int v = 0; v < nv; ++v)
    if (g.var[3 * v + 2] >= 0 && ref.points[v].z() == 1.0) {
      g.var[3 * v + 2] = shared;
      members.push_back(v);
    }
  ASSERT_GE(members.size(), 4u);
  // Renumber variables densely.
  std::vector<int> remap(g.nvar, -1);
  int n = 0;
  for (int& v : g.var)
    if (v >= 0) {
      if (remap[v] < 0) remap[v] = n++;
      v = remap[v];
    }
  const Eigen::VectorXd x_init = solve::flatten(g.mesh.points);
  const solve::LinearReduction R = solve::index_reduction(g.var, n, x_init);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < 3 * nv; ++i)
    if (g.var[i] >= 0) y[g.var[i]] = x_init[i];
  y[remap[shared]] = 1.3;
  solve::UntangleOptions o;
  o.attractions.push_back({0, Vec3(0, 0, 0), 1.0});  // a fixed vertex: attraction has no effect
  const solve::UntangleResult r = solve::untangle(solve::reference_elements(ref.points, ref.cells), R, y, o);
  EXPECT_TRUE(r.untangled);
  const std::vector<Vec3> p = solve::unflatten(R.apply(y));
  EXPECT_EQ(inverted_count(g.mesh, p), 0);
  for (int v : members) EXPECT_EQ(p[v].z(), p[members.front()].z());
  EXPECT_NEAR(p[members.front()].z(), 1.0, 0.05);
}

TEST(Untangle, AttractionPullsFreeVertex) {
  // One tet, all vertices free but vertex 0..2 attracted strongly to translated targets:
  // the tet follows while staying positive.
  const std::vector<Vec3> ref{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<std::array<int, 4>> tets{{0, 1, 2, 3}};
  const solve::LinearReduction R = solve::identity_reduction(4);
  Eigen::VectorXd y = solve::flatten(ref);
  solve::UntangleOptions o;
  for (int v = 0; v < 3; ++v) o.attractions.push_back({v, ref[v] + Vec3(5, 0, 0), 100.0});
  const auto r = solve::untangle(solve::reference_elements(ref, tets), R, y, o);
  EXPECT_TRUE(r.untangled);
  const auto p = solve::unflatten(y);
  for (int v = 0; v < 3; ++v) EXPECT_NEAR((p[v] - ref[v] - Vec3(5, 0, 0)).norm(), 0.0, 1e-2);
}

// --- deformation and certification ------------------------------------------------------------

struct Constructed {
  construct::DeformResult def;
  construct::Certificate cert;
  quality::MapDistortion dist;
};

Constructed deform_and_certify(const core::TetMesh& mesh, const std::vector<core::Tri>& tris,
                               const std::vector<int>& labels, const construct::DeformOptions& o = {}) {
  Constructed c;
  c.def = construct::deform_to_polycube(mesh, tris, labels, o);
  core::PolycubeMap map;
  map.tets = c.def.mesh.cells;
  map.model = c.def.mesh.points;
  map.polycube = c.def.polycube;
  c.cert = construct::certify_polycube_map(map, c.def.boundary, c.def.labels);
  quality::DistortionOptions dopt;
  dopt.normalize_volume = true;
  c.dist = quality::map_distortion(c.def.mesh, c.def.polycube, dopt);
  const Verdict v = independent_check(map.tets, map.model, map.polycube, c.def.boundary, c.def.labels);
  EXPECT_EQ(v.bad_model, 0);
  EXPECT_EQ(v.bad_polycube, 0);
  EXPECT_EQ(v.off_plane, 0);
  EXPECT_EQ(v.unlabeled, 0);
  EXPECT_EQ(v.boundary_faces, static_cast<int>(c.def.boundary.size()));
  return c;
}

TEST(Deform, BoxIsCertifiedNearIdentity) {
  const auto tr = construct::tetrahedralize(cube_surface(6, 10.0));
  std::vector<core::Tri> tris;
  std::vector<int> labels;
  normal_labels(tr.mesh, tris, labels);
  const Constructed c = deform_and_certify(tr.mesh, tris, labels);
  EXPECT_TRUE(c.cert.certified()) << c.cert.reason();
  EXPECT_EQ(c.def.num_charts, 6);
  EXPECT_EQ(c.dist.invalid, 0);
  EXPECT_LT(c.dist.isometric.max, 1.05);
  EXPECT_LT(c.dist.isometric.average, 1.01);
}

//! A cube surface pushed onto a sphere, tetrahedralized, labeled by its normals, repaired.
struct LabeledSphere {
  core::TetMesh mesh;
  std::vector<core::Tri> tris;
  std::vector<int> labels;
};
LabeledSphere labeled_sphere() {
  core::TriMesh s = cube_surface(8, 2.0);
  for (Vec3& p : s.points) p = (p - Vec3(1, 1, 1)).normalized() * 10.0;
  LabeledSphere out;
  out.mesh = construct::tetrahedralize(s).mesh;
  normal_labels(out.mesh, out.tris, out.labels);
  core::TriMesh surf;
  surf.points = out.mesh.points;
  for (const auto& t : out.tris) surf.cells.push_back(t);
  if (!construct::check_labeling(surf, out.labels).valid()) {
    const auto rep = construct::repair_labeling(surf, out.labels);
    if (!rep.valid()) throw core::SolverError("labeling repair failed on the sphere fixture");
    out.labels = rep.labels;
  }
  return out;
}

TEST(Deform, SphereLikeShapeIsCertified) {
  const LabeledSphere sp = labeled_sphere();
  const Constructed c = deform_and_certify(sp.mesh, sp.tris, sp.labels);
  EXPECT_TRUE(c.cert.certified()) << c.cert.reason();
  EXPECT_EQ(c.dist.invalid, 0);
  EXPECT_LT(c.dist.isometric.max, 5.0);
}

TEST(Deform, PlanarityFlowGivesACertifiedSphere) {
  // The same sphere-like shape with the planarity flow as the first polycube: the flow never
  // inverts a tet, and after the snap and the untangling the map is certified.
  const LabeledSphere sp = labeled_sphere();
  construct::DeformOptions o;
  o.flow = true;
  const Constructed c = deform_and_certify(sp.mesh, sp.tris, sp.labels, o);
  EXPECT_TRUE(c.cert.certified()) << c.cert.reason();
  EXPECT_GT(c.def.flow_iterations, 0);
  EXPECT_LE(c.def.flow_residual, 0.05);
  EXPECT_EQ(c.dist.invalid, 0);
}

//! Number of boundary triangles of label l at corner vertex v, for every (corner, chart).
std::vector<int> corner_fans(const std::vector<core::Tri>& tris, const std::vector<int>& labels) {
  std::map<int, std::array<int, 6>> at;
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int v : tris[t]) {
      auto& c = at.try_emplace(v, std::array<int, 6>{}).first->second;
      ++c[labels[t]];
    }
  std::vector<int> fans;
  for (const auto& [v, c] : at) {
    const bool corner = (c[0] + c[1] > 0) && (c[2] + c[3] > 0) && (c[4] + c[5] > 0);
    if (!corner) continue;
    for (int k : c)
      if (k > 0) fans.push_back(k);
  }
  return fans;
}

TEST(Deform, CornerFansAreWidened) {
  // The cube's corners have a one- or two-triangle fan per chart; min_fan asks for 4.
  const auto tr = construct::tetrahedralize(cube_surface(3, 10.0));
  std::vector<core::Tri> tris;
  std::vector<int> labels;
  normal_labels(tr.mesh, tris, labels);
  const std::vector<int> before = corner_fans(tris, labels);
  ASSERT_EQ(before.size(), 24u);  // 8 corners x 3 charts
  EXPECT_LT(*std::min_element(before.begin(), before.end()), 4);
  construct::DeformOptions o;
  o.min_fan = 4;
  const Constructed c = deform_and_certify(tr.mesh, tris, labels, o);
  EXPECT_TRUE(c.cert.certified()) << c.cert.reason();
  const std::vector<int> after = corner_fans(c.def.boundary, c.def.labels);
  ASSERT_EQ(after.size(), 24u);
  EXPECT_GE(*std::min_element(after.begin(), after.end()), 4);
  EXPECT_GT(c.def.split_fan_edges, 0);
}

TEST(Predeform, TurnsNormalsTowardsTheAxes) {
  // A sphere: its normals are as far from the axes as a closed surface gets on average.
  core::TriMesh s = cube_surface(8, 2.0);
  for (Vec3& p : s.points) p = (p - Vec3(1, 1, 1)).normalized() * 10.0;
  const auto tr = construct::tetrahedralize(s);
  const core::TetBoundary b = core::boundary(tr.mesh);
  std::vector<core::Tri> tris;
  for (const auto& t : b.surface.cells) tris.push_back({b.vertex_map[t[0]], b.vertex_map[t[1]], b.vertex_map[t[2]]});
  construct::PredeformOptions o;
  o.iterations = 30;
  const construct::PredeformResult r = construct::predeform(tr.mesh, tris, o);
  ASSERT_EQ(r.points.size(), tr.mesh.points.size());
  EXPECT_GT(r.iterations, 0);
  EXPECT_GT(r.misalignment_before, 0.05);
  EXPECT_LT(r.misalignment_after, 0.5 * r.misalignment_before);
  // Recompute the figure here: area-weighted 1 - max |n . axis| of the deformed surface.
  double sum = 0, area = 0;
  for (const auto& t : tris) {
    const Vec3 n = (r.points[t[1]] - r.points[t[0]]).cross(r.points[t[2]] - r.points[t[0]]);
    sum += n.norm() - n.cwiseAbs().maxCoeff();
    area += n.norm();
  }
  EXPECT_NEAR(sum / area, r.misalignment_after, 1e-12);
  // As rigid as possible: the sphere becomes a rounded cube of about its volume (measured:
  // 0.84 of it), it neither collapses nor inflates.
  auto volume = [&](const std::vector<Vec3>& P) {
    double v = 0;
    for (const auto& c : tr.mesh.cells) v += (P[c[1]] - P[c[0]]).dot((P[c[2]] - P[c[0]]).cross(P[c[3]] - P[c[0]])) / 6;
    return v;
  };
  EXPECT_GT(volume(r.points) / volume(tr.mesh.points), 0.7);
  EXPECT_LT(volume(r.points) / volume(tr.mesh.points), 1.1);
  // Deterministic.
  const construct::PredeformResult again = construct::predeform(tr.mesh, tris, o);
  EXPECT_EQ(again.points, r.points);
}

TEST(Construct, RotatedBoxIsAlignedAndKeepsItsPositions) {
  // A box given at an angle to the axes: the construction rotates it back before the labeling
  // (one chart per face), and the written model keeps the input's coordinates bit for bit.
  core::TriMesh s = cube_surface(4, 10.0);
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (Vec3& p : s.points) p = Q * p;
  const construct::ConstructResult r = construct::construct_polycube(s);
  EXPECT_FALSE(r.axis_rotation.rotation.isIdentity());
  EXPECT_LT(r.axis_rotation.energy_after, r.axis_rotation.energy_before);
  EXPECT_EQ(r.charts, 6);
  EXPECT_EQ(r.corners, 8);
  const Verdict v = independent_check(r.map.tets, r.map.model, r.map.polycube, r.boundary, r.labels);
  EXPECT_TRUE(test::certified(v)) << "bad model " << v.bad_model << ", bad polycube " << v.bad_polycube
                                  << ", off plane " << v.off_plane << ", wrong facing " << v.wrong_facing;
  std::set<std::array<double, 3>> model;
  for (const Vec3& p : r.map.model) model.insert({p.x(), p.y(), p.z()});
  for (const Vec3& p : s.points) EXPECT_EQ(model.count({p.x(), p.y(), p.z()}), 1u);
}

TEST(Certify, RejectsInvertedAndOffPlaneMaps) {
  const auto tr = construct::tetrahedralize(cube_surface(3, 1.0));
  std::vector<core::Tri> tris;
  std::vector<int> labels;
  normal_labels(tr.mesh, tris, labels);
  core::PolycubeMap map;
  map.tets = tr.mesh.cells;
  map.model = tr.mesh.points;
  map.polycube = tr.mesh.points;
  EXPECT_TRUE(construct::certify_polycube_map(map, tris, labels).certified());
  // A boundary vertex moved off its plane by one ulp.
  core::PolycubeMap off = map;
  const int v = tris.front()[0];
  const int a = labels.front() / 2;
  off.polycube[v][a] = std::nextafter(off.polycube[v][a], 2.0);
  const auto c1 = construct::certify_polycube_map(off, tris, labels);
  EXPECT_FALSE(c1.certified());
  EXPECT_GT(c1.off_plane, 0);
  EXPECT_THROW(construct::require_certified(c1), core::GeometryError);
  // An interior vertex pushed outside: tets inverted.
  core::PolycubeMap inv = map;
  const core::TetBoundary b = core::boundary(tr.mesh);
  std::vector<char> on_b(map.model.size(), 0);
  for (int w : b.vertex_map) on_b[w] = 1;
  int interior = -1;
  for (int i = 0; i < static_cast<int>(on_b.size()) && interior < 0; ++i)
    if (!on_b[i]) interior = i;
  ASSERT_GE(interior, 0);
  inv.polycube[interior] = Vec3(5, 5, 5);
  const auto c2 = construct::certify_polycube_map(inv, tris, labels);
  EXPECT_FALSE(c2.certified());
  EXPECT_GT(c2.inverted_polycube, 0);
  // Wrong labels (a +X face labeled -X) face the wrong way.
  std::vector<int> bad = labels;
  for (int& l : bad)
    if (l == 0) l = 1;
  EXPECT_GT(construct::certify_polycube_map(map, tris, bad).wrong_facing, 0);
}

}  // namespace
}  // namespace polycube
