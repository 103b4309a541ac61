// The pad stage's other end of selective padding's trade-off (pipeline/fewest_hexes.h): taken
// only after a plan that padded every boundary facet, padded only when it pads at most half of
// them, and the same mesh whether it was made beside that plan or when taken.
#include "padding/padding.h"
#include "pipeline/fewest_hexes.h"
#include "pipeline/input.h"
#include "pipeline/pipeline.h"

#include "support/fixtures.h"
#include "support/shapes.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>

namespace polycube {
namespace {

using core::Vec3;

//! An 8 x 8 x 8 grid whose top-front edge is chamfered at 45°: the facets along it are distorted
//! (D = 1), so the analysis gives a hard set there and nowhere near the other edges.
core::HexMesh chamfered_grid() {
  core::HexMesh m = test::hex_grid(8, 8, 8);
  for (Vec3& p : m.points)
    if (p.y() == 0.0 && p.z() == 8.0) p = Vec3(p.x(), 0.5, 7.5);
  return m;
}

int count_boundary_facets(const core::HexMesh& m) {
  const std::vector<std::uint8_t> b = padding::boundary_selection(m);
  return static_cast<int>(std::count(b.begin(), b.end(), 1));
}

TEST(PadStage, TheFewestHexesArePaddedOnlyAfterAPlanOfTheWholeBoundary) {
  const core::HexMesh hex = chamfered_grid();
  const int whole = count_boundary_facets(hex);
  ASSERT_EQ(whole, 6 * 64);
  pipeline::ConstructInput in;
  in.target = test::make_box(8.0, 8.0, 8.0, 8);
  pipeline::RunOptions o;                   // selective padding, λ = 1, padding_fewest_too
  o.padding_options.run_optimizer = false;  // the layer as inserted: the plan is what is tested

  // A plan at λ = 1 that was selective already: nothing more is planned.
  {
    pipeline::FewestHexesCandidate candidate(hex, in, o);
    candidate.planned(whole - 1);
    pipeline::RunResult partial;
    partial.padding_selected_facets = whole - 1;
    EXPECT_FALSE(candidate.take("selective", partial));
    EXPECT_EQ(partial.padding_solve_seconds, -1);
    EXPECT_EQ(partial.padding_fewest_hexes, "");
  }

  // Switched off (an explicit --padding-lambda): nothing either.
  pipeline::RunOptions off = o;
  off.padding_fewest_too = false;
  pipeline::FewestHexesCandidate none(hex, in, off);
  none.planned(whole);
  pipeline::RunResult r_off;
  r_off.padding_selected_facets = whole;
  EXPECT_FALSE(none.take("selective", r_off));
  EXPECT_EQ(r_off.padding_solve_seconds, -1);

  // After a plan of the whole boundary: the λ = 0 plan is a layer under the chamfer only.
  pipeline::FewestHexesCandidate candidate(hex, in, o);
  candidate.planned(whole);
  pipeline::RunResult r;
  r.padding_selected_facets = whole;
  const std::optional<padding::PadResult> p = candidate.take("selective (lambda 0)", r);
  ASSERT_TRUE(p);
  EXPECT_GT(r.padding_hard_facets, 0);
  EXPECT_GT(r.padding_selected_facets, 0);
  EXPECT_LE(r.padding_selected_facets, whole / 2);
  EXPECT_EQ(p->added_hexes, r.padding_selected_facets);
  EXPECT_EQ(r.padding_added, p->added_hexes);
  EXPECT_EQ(r.padding, "selective (lambda 0)");
  EXPECT_EQ(p->mesh.num_cells(), hex.num_cells() + p->added_hexes);
  // Only hexes near the chamfered edge are padded (HF is its facets and the three rings the
  // propagation adds): every new hex comes from a hex in the quadrant of that edge.
  for (std::size_t h = 0; h < p->padding_layer.size(); ++h) {
    if (!p->padding_layer[h]) continue;
    const auto& cell = hex.cells[p->source_hex[h]];
    Vec3 c = Vec3::Zero();
    for (int v : cell) c += hex.points[v] / 8.0;
    EXPECT_LT(c.y(), 4.0) << "new hex " << h;
    EXPECT_GT(c.z(), 4.0) << "new hex " << h;
  }
}

TEST(PadStage, APlanOfMoreThanHalfTheBoundaryAtLambdaZeroIsNotPadded) {
  // Every boundary hex distorted: the grid's corners pulled in, so every boundary facet is
  // hard and the λ = 0 plan is the whole boundary again.
  core::HexMesh hex = test::hex_grid(4, 4, 4);
  for (Vec3& p : hex.points) {
    const bool corner_x = p.x() == 0.0 || p.x() == 4.0, corner_y = p.y() == 0.0 || p.y() == 4.0,
               corner_z = p.z() == 0.0 || p.z() == 4.0;
    if (corner_x + corner_y + corner_z >= 2) p = Vec3(2.0, 2.0, 2.0) + 0.8 * (p - Vec3(2.0, 2.0, 2.0));
  }
  const int whole = count_boundary_facets(hex);
  pipeline::ConstructInput in;
  in.target = test::make_box(4.0, 4.0, 4.0, 4);
  pipeline::RunOptions o;
  o.padding_analysis.threshold = 1.0;  // every boundary hex analysed
  o.padding_options.run_optimizer = false;
  pipeline::FewestHexesCandidate candidate(hex, in, o);
  candidate.planned(whole);
  pipeline::RunResult r;
  r.padding_selected_facets = whole;
  EXPECT_FALSE(candidate.take("selective", r));
  EXPECT_GT(r.padding_solve_seconds, -1);  // it was planned
  EXPECT_NE(r.padding_fewest_hexes.find("not padded (more than 50 %)"), std::string::npos) << r.padding_fewest_hexes;
}

TEST(PadStage, TheCandidateMadeBesideThePlanIsTheOneMadeWhenTaken) {
  const core::HexMesh hex = chamfered_grid();
  const int whole = count_boundary_facets(hex);
  pipeline::ConstructInput in;
  in.target = test::make_box(8.0, 8.0, 8.0, 8);
  const pipeline::RunOptions o;  // optimized, as in `run`
  const auto made = [&](int threads, bool told_before) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    pipeline::FewestHexesCandidate candidate(hex, in, o);
    // Told while it plans, or only when the plan at λ = 1 took longer than its own plan.
    if (told_before) candidate.planned(whole);
    pipeline::RunResult r;
    r.padding_selected_facets = whole;
    if (!told_before) candidate.planned(whole);
    std::optional<padding::PadResult> p = candidate.take("selective (lambda 0)", r);
    EXPECT_TRUE(p);
    return p ? p->mesh : core::HexMesh{};
  };
  const core::HexMesh when_taken = made(1, true);
  ASSERT_GT(when_taken.num_cells(), hex.num_cells());
  for (bool told_before : {true, false}) {
    const core::HexMesh beside = made(2, told_before);
    EXPECT_EQ(beside.cells, when_taken.cells);
    ASSERT_EQ(beside.points.size(), when_taken.points.size());
    for (std::size_t v = 0; v < beside.points.size(); ++v)
      ASSERT_EQ(beside.points[v], when_taken.points[v]) << "vertex " << v;  // bit for bit
  }
}

TEST(PadStage, ACandidateNoLongerWantedIsLeftUntakenAndWaitedFor) {
  const core::HexMesh hex = chamfered_grid();
  pipeline::ConstructInput in;
  in.target = test::make_box(8.0, 8.0, 8.0, 8);
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  for (int selected : {0, 100}) {
    pipeline::FewestHexesCandidate candidate(hex, in, pipeline::RunOptions{});
    candidate.planned(selected);  // the plan at λ = 1 was selective: the candidate stops after its plan
    pipeline::RunResult r;
    r.padding_selected_facets = selected;
    EXPECT_FALSE(candidate.take("selective", r));
    EXPECT_EQ(r.padding_solve_seconds, -1);  // nothing of the candidate recorded
  }  // the destructor waits for the candidate's thread: `hex` and `in` outlive it
}

}  // namespace
}  // namespace polycube
