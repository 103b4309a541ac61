//! The simplification and its fallbacks (see simplify.h).
#include "simplify/simplify.h"

#include "core/log.h"
#include "core/stopwatch.h"
#include "structure/structure.h"
#include "structure/validate.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace polycube::simplify {

namespace {

//! Align the corners, count the domains before and after, fit: one step's work.
void align_and_fit(const core::PolycubeMap& map, const structure::PolycubeStructure& s, const SimplifyOptions& o,
                   const AlignOptions& align, SimplifyResult& r) {
  r.alignment = align_corners(s, align);
  if (o.count_domains) {
    const core::Stopwatch t;
    const auto& sys = r.alignment.system;
    std::array<std::vector<double>, 3> before, after;
    for (int a = 0; a < 3; ++a) {
      before[a] = sys.axes[a].coordinate;
      after[a].assign(r.alignment.class_value[a].begin(), r.alignment.class_value[a].end());
    }
    r.before = count_domains(sys, s, before);
    r.after = count_domains(sys, s, after);
    r.seconds_domains += t.seconds();
  }
  if (o.fit_map) r.fit = fit_polycube(map, s, r.alignment, o.fit);
}

//! Corners "where the inverted tets are": for each tet the fit left inverted, its nearest
//! corner in the input polycube and every corner at most twice as far. Their alignments are
//! what forced the fit through those tets. Empty when no tet is inverted.
std::vector<char> corners_near_inverted(const core::PolycubeMap& map, const structure::PolycubeStructure& s,
                                        const FitResult& fit) {
  std::vector<char> frozen;
  if (fit.map.polycube.size() != map.polycube.size()) return frozen;
  for (const core::Tet& t : map.tets) {
    if (core::positive_tet(fit.map.polycube, t)) continue;
    if (frozen.empty()) frozen.assign(s.corners.size(), 0);
    const core::Vec3 c = 0.25 * (map.polycube[t[0]] + map.polycube[t[1]] + map.polycube[t[2]] + map.polycube[t[3]]);
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& corner : s.corners) nearest = std::min(nearest, (corner.position - c).norm());
    for (std::size_t k = 0; k < s.corners.size(); ++k)
      if ((s.corners[k].position - c).norm() <= 2.0 * nearest) frozen[k] = 1;
  }
  return frozen;
}

//! Why a step's fit failed, in one line.
std::string failure_of(SimplifyStep step, const FitResult& fit, bool injected) {
  std::string why = injected ? std::string("injected failure") : std::string();
  for (const auto& f : fit.failures) why += (why.empty() ? "" : "; ") + f;
  return fmt::format("{}: {}", step_name(step), why);
}

//! The options of the step after a failed one (`failed` is the failed step's result).
AlignOptions next_step_options(SimplifyStep next, const core::PolycubeMap& map, const structure::PolycubeStructure& s,
                               const SimplifyOptions& o, SimplifyResult& failed) {
  AlignOptions align = o.align;
  if (next == SimplifyStep::FewerAlignments) {
    align.frozen_corners = corners_near_inverted(map, s, failed.fit);
    failed.frozen_corners = static_cast<int>(std::count(align.frozen_corners.begin(), align.frozen_corners.end(), 1));
    if (align.frozen_corners.empty()) align.lambda_min = 1.0;  // nothing inverted to point at: one iteration
  } else {
    align.lambda_min = std::numeric_limits<double>::infinity();  // Unaligned: no iteration at all
  }
  return align;
}

//! The map with its polycube moved so that its bounding box starts at the origin. The lattice
//! the corners are aligned on is anchored there, on the shape, not at the origin of whatever
//! coordinates the model came in: a model moved by 1e7 rounds its corners as it does in place.
core::PolycubeMap anchored_at_origin(const core::PolycubeMap& map) {
  core::PolycubeMap out = map;
  const core::Vec3 lo = core::bounding_box(map.polycube).min;
  for (core::Vec3& p : out.polycube) p -= lo;
  return out;
}

}  // namespace

const char* step_name(SimplifyStep step) {
  switch (step) {
    case SimplifyStep::Aligned: return "aligned";
    case SimplifyStep::FewerAlignments: return "fewer alignments";
    case SimplifyStep::Unaligned: return "unaligned";
    case SimplifyStep::None: break;
  }
  return "none";
}

SimplifyResult simplify_map(const core::PolycubeMap& input, const SimplifyOptions& options) {
  SimplifyResult r;
  core::Stopwatch t;
  structure::validate_map(input);
  const core::PolycubeMap map = anchored_at_origin(input);
  r.seconds_validate = t.seconds();
  t.restart();
  const auto s = structure::extract_structure(map);
  r.seconds_structure = t.seconds();
  r.corners = static_cast<int>(s.corners.size());
  r.edges = static_cast<int>(s.edges.size());
  r.charts = static_cast<int>(s.charts.size());

  AlignOptions align = options.align;
  for (int k = 0;; ++k) {
    r.step = static_cast<SimplifyStep>(k);
    align_and_fit(map, s, options, align, r);
    const bool injected = k < options.inject_failed_steps;
    if (!options.fit_map || (r.fit.certified && !injected)) return r;
    r.tried.push_back(failure_of(r.step, r.fit, injected));
    const auto next = static_cast<SimplifyStep>(k + 1);
    if (!options.fallbacks || next == SimplifyStep::None) break;
    align = next_step_options(next, map, s, options, r);
    core::logger().info("simplify: {}; trying {}", r.tried.back(), step_name(next));
  }
  r.fit.certified = false;  // an injected failure of the last step counts as one
  r.step = SimplifyStep::None;
  return r;
}

}  // namespace polycube::simplify
