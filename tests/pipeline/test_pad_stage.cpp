// The pad stage's other end of selective padding's trade-off (pipeline/stage_steps.h,
// pad_with_fewest_hexes): planned only after a plan that padded every boundary facet, and
// padded only when it pads at most half of them.
#include "padding/padding.h"
#include "pipeline/input.h"
#include "pipeline/pipeline.h"
#include "pipeline/stage_steps.h"

#include "support/fixtures.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

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
  pipeline::RunResult partial;
  partial.padding_selected_facets = whole - 1;
  EXPECT_FALSE(pipeline::pad_with_fewest_hexes(hex, in, o, "selective", partial));
  EXPECT_EQ(partial.padding_solve_seconds, -1);
  EXPECT_EQ(partial.padding_fewest_hexes, "");

  // Switched off (an explicit --padding-lambda): nothing either.
  pipeline::RunOptions off = o;
  off.padding_fewest_too = false;
  pipeline::RunResult r_off;
  r_off.padding_selected_facets = whole;
  EXPECT_FALSE(pipeline::pad_with_fewest_hexes(hex, in, off, "selective", r_off));

  // After a plan of the whole boundary: the λ = 0 plan is a layer under the chamfer only.
  pipeline::RunResult r;
  r.padding_selected_facets = whole;
  const std::optional<padding::PadResult> p = pipeline::pad_with_fewest_hexes(hex, in, o, "selective (lambda 0)", r);
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
  pipeline::RunResult r;
  r.padding_selected_facets = whole;
  EXPECT_FALSE(pipeline::pad_with_fewest_hexes(hex, in, o, "selective", r));
  EXPECT_GT(r.padding_solve_seconds, -1);  // it was planned
  EXPECT_NE(r.padding_fewest_hexes.find("not padded (more than 50 %)"), std::string::npos) << r.padding_fewest_hexes;
}

}  // namespace
}  // namespace polycube
