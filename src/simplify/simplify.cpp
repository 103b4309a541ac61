#include "simplify/simplify.h"
#include "core/stopwatch.h"

#include "structure/structure.h"
#include "structure/validate.h"


namespace polycube::simplify {

namespace {
}  // namespace

SimplifyResult simplify_map(const core::PolycubeMap& map, const SimplifyOptions& options) {
  SimplifyResult r;
  core::Stopwatch t;
  structure::validate_map(map);
  r.seconds_validate = t.seconds();
  t.restart();
  const auto s = structure::extract_structure(map);
  r.seconds_structure = t.seconds();
  r.corners = static_cast<int>(s.corners.size());
  r.edges = static_cast<int>(s.edges.size());
  r.charts = static_cast<int>(s.charts.size());
  r.alignment = align_corners(s, options.align);
  if (options.count_domains) {
    t.restart();
    const auto& sys = r.alignment.system;
    std::array<std::vector<double>, 3> before, after;
    for (int a = 0; a < 3; ++a) {
      before[a] = sys.axes[a].coordinate;
      after[a].assign(r.alignment.class_value[a].begin(), r.alignment.class_value[a].end());
    }
    r.before = count_domains(sys, s, before);
    r.after = count_domains(sys, s, after);
    r.seconds_domains = t.seconds();
  }
  if (options.fit_map) r.fit = fit_polycube(map, s, r.alignment, options.fit);
  return r;
}

}  // namespace polycube::simplify
