// Corner pairing, constraint system and alignment on polycubes built in code (thesis §3.3–3.5).
#include "core/errors.h"
#include "simplify/corner_alignment.h"
#include "simplify/corner_pairing.h"
#include "simplify/corner_system.h"
#include "simplify/domain_count.h"
#include "structure/structure.h"
#include "polycube_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace polycube {
namespace {

using simplify::AlignOptions;

//! Corner id at a polycube position (exact), or -1.
int corner_at(const structure::PolycubeStructure& s, const core::Vec3& p) {
  for (std::size_t c = 0; c < s.corners.size(); ++c)
    if (s.corners[c].position == p) return static_cast<int>(c);
  return -1;
}

std::array<std::vector<double>, 3> values_of(const simplify::AlignResult& r) {
  std::array<std::vector<double>, 3> v;
  for (int a = 0; a < 3; ++a) v[a].assign(r.class_value[a].begin(), r.class_value[a].end());
  return v;
}

std::array<std::vector<double>, 3> original_of(const simplify::CornerSystem& sys) {
  std::array<std::vector<double>, 3> v;
  for (int a = 0; a < 3; ++a) v[a] = sys.axes[a].coordinate;
  return v;
}

TEST(DelaunayPairs, CubeCornersGiveTheTwelveEdgesAndNoDuplicates) {
  std::vector<core::Vec3> pts;
  for (int i = 0; i < 8; ++i) pts.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const auto pairs = simplify::delaunay_pairs(pts);
  std::set<std::array<int, 2>> set(pairs.begin(), pairs.end());
  EXPECT_EQ(set.size(), pairs.size());
  for (const auto& [i, j] : pairs) {
    EXPECT_LT(i, j);
    EXPECT_GE(i, 0);
    EXPECT_LT(j, 8);
  }
  int edges = 0;  // the 12 cube edges connect points differing in one bit: all Delaunay edges
  for (int i = 0; i < 8; ++i)
    for (int b = 0; b < 3; ++b)
      if (!(i & (1 << b))) edges += set.count({i, i | (1 << b)}) ? 1 : 0;
  EXPECT_EQ(edges, 12);
  EXPECT_EQ(simplify::delaunay_pairs(pts), pairs);  // deterministic
}

TEST(DelaunayPairs, SmallInputs) {
  EXPECT_TRUE(simplify::delaunay_pairs({}).empty());
  const auto two = simplify::delaunay_pairs({core::Vec3(0, 0, 0), core::Vec3(1, 2, 3)});
  ASSERT_EQ(two.size(), 1U);
  EXPECT_EQ(two[0], (std::array<int, 2>{0, 1}));
}

TEST(CornerSystem, ClassesAndConstraintsOfTheComb) {
  const auto s = structure::extract_structure(test::comb(0.1));
  const auto sys = simplify::build_corner_system(s, 10.0);
  // y: floors at 0, 1.0, 1.1 and tops at 3 (all tops are linked through the x-/z-edges? no:
  // each top is its own chart, but they share y = 3 and are merged as coincident)
  EXPECT_EQ(sys.axes[0].num_classes(), 6);
  EXPECT_EQ(sys.axes[1].num_classes(), 4);
  EXPECT_EQ(sys.axes[2].num_classes(), 2);
  for (const auto& ax : sys.axes) {
    for (std::size_t k = 1; k < ax.coordinate.size(); ++k) EXPECT_LT(ax.coordinate[k - 1], ax.coordinate[k]);
    EXPECT_LE(static_cast<int>(ax.constraints.size()), ax.constraints_before_reduction);
    for (const auto& c : ax.constraints) {
      EXPECT_LT(c.from, c.to);
      // at scale 10 every gap of the input is >= 1: the scaled input satisfies every constraint
      EXPECT_GE(ax.coordinate[c.to] - ax.coordinate[c.from], c.weight - 1e-9);
    }
  }
  // the input is embedded: no contact at its own coordinates
  EXPECT_TRUE(simplify::find_contacts(sys, s, original_of(sys)).empty());
  // points: inside the base, inside a tooth, in a notch, outside
  const auto v = original_of(sys);
  EXPECT_TRUE(simplify::inside_polycube(sys, s, v, core::Vec3(25, 5, 5)));
  EXPECT_TRUE(simplify::inside_polycube(sys, s, v, core::Vec3(5, 25, 5)));
  EXPECT_FALSE(simplify::inside_polycube(sys, s, v, core::Vec3(15, 25, 5)));
  EXPECT_FALSE(simplify::inside_polycube(sys, s, v, core::Vec3(-1, 5, 5)));
}

TEST(CornerPairing, PrunedPairsObeyTheThreeRules) {
  const auto s = structure::extract_structure(test::comb(0.1));
  const auto sys = simplify::build_corner_system(s, 10.0);
  std::vector<core::Vec3> pos;
  for (const auto& c : s.corners) pos.push_back(10.0 * c.position);
  simplify::PairingStats st;
  const auto pairs = simplify::pair_corners(
      s, pos, [&](int axis, int a, int b) { return sys.axes[axis].corner_class[a] != sys.axes[axis].corner_class[b]; },
      {}, &st);
  EXPECT_GT(st.delaunay, 0);
  EXPECT_EQ(st.kept, static_cast<int>(pairs.size()));
  std::set<std::pair<int, int>> edge_pairs;
  std::vector<std::set<int>> nb(s.corners.size());
  for (const auto& e : s.edges) {
    edge_pairs.insert({std::min(e.corners[0], e.corners[1]), std::max(e.corners[0], e.corners[1])});
    nb[e.corners[0]].insert(e.corners[1]);
    nb[e.corners[1]].insert(e.corners[0]);
  }
  for (const auto& p : pairs) {
    EXPECT_LT(p.a, p.b);
    EXPECT_FALSE(edge_pairs.count({p.a, p.b})) << "rule 1";
    for (int n : nb[p.a]) EXPECT_FALSE(nb[p.b].count(n)) << "rule 2";
    EXPECT_NE(sys.axes[p.axis].corner_class[p.a], sys.axes[p.axis].corner_class[p.b]);
    EXPECT_DOUBLE_EQ(p.distance, std::abs(pos[p.a][p.axis] - pos[p.b][p.axis]));
  }
  // the notch floors' inner corners (2,1.0,0) and (3,1.1,0) are a candidate along y
  const int c0 = corner_at(s, core::Vec3(2, 1.0, 0)), c1 = corner_at(s, core::Vec3(3, 1.1, 0));
  ASSERT_GE(c0, 0);
  ASSERT_GE(c1, 0);
  EXPECT_TRUE(std::any_of(pairs.begin(), pairs.end(), [&](const simplify::CornerPair& p) {
    return p.a == std::min(c0, c1) && p.b == std::max(c0, c1) && p.axis == 1;
  }));
}

// Thesis fig. 3.5: two notches whose floors differ by 0.1 (one lattice unit at scale 10):
// the best alignment by hand puts both floors on one plane, one layer of blocks less.
TEST(CornerAlignment, CombAlignsTheNotchFloors) {
  const auto s = structure::extract_structure(test::comb(0.1));
  AlignOptions o;
  o.scale = 10.0;
  const auto r = simplify::align_corners(s, o);
  const int c0 = corner_at(s, core::Vec3(2, 1.0, 0)), c1 = corner_at(s, core::Vec3(3, 1.1, 0));
  EXPECT_EQ(r.corners[c0].y(), r.corners[c1].y());
  EXPECT_EQ(r.planes_before, (std::array<int, 3>{6, 4, 2}));
  EXPECT_EQ(r.planes_after, (std::array<int, 3>{6, 3, 2}));
  EXPECT_TRUE(r.converged);
  EXPECT_FALSE(r.aligned.empty());
  // integer corners, every constraint satisfied, nothing else moved (x and z are integral already)
  for (std::size_t c = 0; c < s.corners.size(); ++c)
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(r.corners[c][a], std::round(r.corners[c][a]));
      if (a != 1) {
        EXPECT_EQ(r.corners[c][a], 10.0 * s.corners[c].position[a]);
      }
    }
  for (int a = 0; a < 3; ++a)
    for (const auto& k : r.system.axes[a].constraints)
      EXPECT_GE(r.class_value[a][k.to] - r.class_value[a][k.from], k.weight);
  EXPECT_TRUE(simplify::find_contacts(r.system, s, values_of(r)).empty());
  // fewer blocks and patches
  const auto before = simplify::count_domains(r.system, s, original_of(r.system));
  const auto after = simplify::count_domains(r.system, s, values_of(r));
  EXPECT_LT(after.hex_domains, before.hex_domains);
  EXPECT_LT(after.quad_domains, before.quad_domains);
  // the shape term: both floors moved by one unit at most
  EXPECT_LE(r.max_displacement, 1.0 + 1e-9);
}

TEST(CornerAlignment, LambdaMinOneRunsOneIteration) {
  const auto s = structure::extract_structure(test::comb(0.1));
  AlignOptions o;
  o.scale = 10.0;
  o.lambda_min = 1.0;
  const auto r = simplify::align_corners(s, o);
  EXPECT_EQ(r.iterations.size(), 1U);
  EXPECT_EQ(r.stop_reason, "lambda_min");
  // at lambda = 1 moving a floor (4 corners) by one unit costs more than two unaligned pairs
  EXPECT_EQ(r.planes_after[1], 4);
}

TEST(CornerAlignment, FrozenCornersAreNeverPaired) {
  const auto s = structure::extract_structure(test::comb(0.1));
  AlignOptions o;
  o.scale = 10.0;
  const int floor = corner_at(s, core::Vec3(3, 1.1, 0));
  o.frozen_corners.assign(s.corners.size(), 0);
  o.frozen_corners[static_cast<std::size_t>(floor)] = 1;
  const auto r = simplify::align_corners(s, o);
  for (const auto& p : r.aligned) EXPECT_TRUE(p.a != floor && p.b != floor) << p.a << " " << p.b;
  // Every corner frozen: nothing is aligned, the corners only go to the lattice.
  o.frozen_corners.assign(s.corners.size(), 1);
  const auto none = simplify::align_corners(s, o);
  EXPECT_TRUE(none.aligned.empty());
  EXPECT_EQ(none.planes_after, none.planes_before);
  o.frozen_corners.assign(2, 0);  // one flag per corner, or none
  EXPECT_THROW(simplify::align_corners(s, o), core::InputError);
}

// Thesis fig. 3.6: the bump's top (y = 2.9) nearly touches the top bar's underside (y = 3).
// With rule 3 off the pairing proposes aligning them; without the separation constraints the
// solution makes the two parts touch, with them the parts stay one lattice unit apart.
TEST(CornerAlignment, SeparationKeepsNonAdjacentPartsApart) {
  const auto s = structure::extract_structure(test::c_with_bump(0.1));
  const int bump = corner_at(s, core::Vec3(2.5, 2.9, 0));
  const int under = corner_at(s, core::Vec3(1, 3, 0));
  ASSERT_GE(bump, 0);
  ASSERT_GE(under, 0);
  AlignOptions o;
  o.scale = 10.0;
  o.exterior_rule = false;

  o.system.separation = false;
  const auto loose = simplify::align_corners(s, o);
  EXPECT_EQ(loose.corners[bump].y(), loose.corners[under].y()) << "unconstrained: the parts touch";
  EXPECT_FALSE(simplify::find_contacts(loose.system, s, values_of(loose)).empty());

  o.system.separation = true;
  const auto tight = simplify::align_corners(s, o);
  EXPECT_LE(tight.corners[bump].y() + 1, tight.corners[under].y());
  EXPECT_TRUE(simplify::find_contacts(tight.system, s, values_of(tight)).empty());
  for (int a = 0; a < 3; ++a)
    for (const auto& k : tight.system.axes[a].constraints)
      EXPECT_GE(tight.class_value[a][k.to] - tight.class_value[a][k.from], k.weight);
}

TEST(CornerAlignment, Deterministic) {
  for (const auto& map : {test::comb(0.1), test::c_with_bump(0.1)}) {
    const auto s = structure::extract_structure(map);
    AlignOptions o;
    o.scale = 7.3;
    const auto r1 = simplify::align_corners(s, o);
    const auto r2 = simplify::align_corners(s, o);
    EXPECT_EQ(r1.corners, r2.corners);
    EXPECT_EQ(r1.class_value, r2.class_value);
    ASSERT_EQ(r1.aligned.size(), r2.aligned.size());
    for (std::size_t k = 0; k < r1.aligned.size(); ++k) {
      EXPECT_EQ(r1.aligned[k].a, r2.aligned[k].a);
      EXPECT_EQ(r1.aligned[k].b, r2.aligned[k].b);
      EXPECT_EQ(r1.aligned[k].axis, r2.aligned[k].axis);
    }
  }
}

TEST(CornerAlignment, SmallScaleStillSeparatesEverything) {
  // At scale 1 the comb's notch depths (0.1, 1.0) are below one lattice unit: the constraints
  // force edges to length >= 1 and keep every part apart anyway.
  const auto s = structure::extract_structure(test::comb(0.1));
  AlignOptions o;
  o.scale = 1.0;
  const auto r = simplify::align_corners(s, o);
  EXPECT_TRUE(simplify::find_contacts(r.system, s, values_of(r)).empty());
  for (const auto& e : s.edges) EXPECT_GE(std::abs(r.corners[e.corners[1]][e.axis] - r.corners[e.corners[0]][e.axis]), 1.0);
}

TEST(DomainCount, BoxAndLShape) {
  const auto box = test::grid_polycube({0, 2}, {0, 1}, {0, 3}, [](int, int, int) { return true; });
  const auto sb = structure::extract_structure(box);
  const auto sysb = simplify::build_corner_system(sb, 1.0);
  const auto db = simplify::count_domains(sysb, sb, original_of(sysb));
  EXPECT_EQ(db.hexes, 1);
  EXPECT_EQ(db.hex_domains, 1);
  EXPECT_EQ(db.quad_domains, 6);
  // L shape extruded: the concave edge's two planes cut it into 3 blocks
  const auto l = test::grid_polycube({0, 1, 2}, {0, 1, 2}, {0, 1}, [](int i, int j, int) { return i == 0 || j == 0; });
  const auto sl = structure::extract_structure(l);
  const auto sysl = simplify::build_corner_system(sl, 1.0);
  const auto dl = simplify::count_domains(sysl, sl, original_of(sysl));
  EXPECT_EQ(dl.hexes, 3);
  EXPECT_EQ(dl.hex_domains, 3);
}

}  // namespace
}  // namespace polycube
