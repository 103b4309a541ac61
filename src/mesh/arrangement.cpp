//! The arrangement of a polycube's chart planes (see arrangement.h).
#include "mesh/arrangement.h"

#include "core/errors.h"
#include "core/polycube_map.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <vector>
#include <utility>

namespace polycube::mesh {

int Arrangement::nearest_level(int a, double x) const {
  const auto& l = level[a];
  auto it = std::lower_bound(l.begin(), l.end(), x);
  if (it == l.end()) return static_cast<int>(l.size()) - 1;
  if (it == l.begin()) return 0;
  return (x - *(it - 1) <= *it - x) ? static_cast<int>(it - l.begin()) - 1
                                    : static_cast<int>(it - l.begin());
}

namespace {

//! Add the planes of `extra` to the levels of one axis (see build_arrangement) and move the
//! charts' level indices with them.
void add_extra_levels(std::vector<double>& level, const std::vector<double>& extra, double tol, int axis,
                      const structure::PolycubeStructure& s, std::vector<int>& chart_level) {
  std::vector<double> add;
  for (double x : extra) {
    if (!(x > level.front() + tol && x < level.back() - tol)) continue;
    const auto it = std::lower_bound(level.begin(), level.end(), x);
    if (std::abs(*it - x) > tol && std::abs(*(it - 1) - x) > tol) add.push_back(x);
  }
  if (add.empty()) return;
  std::sort(add.begin(), add.end());
  add.erase(std::unique(add.begin(), add.end(), [tol](double a, double b) { return b - a <= tol; }), add.end());
  std::vector<double> merged;
  std::merge(level.begin(), level.end(), add.begin(), add.end(), std::back_inserter(merged));
  for (std::size_t c = 0; c < s.charts.size(); ++c)
    if (s.charts[c].axis == axis) {
      const double x = level[static_cast<std::size_t>(chart_level[c])];
      chart_level[c] = static_cast<int>(std::lower_bound(merged.begin(), merged.end(), x) - merged.begin());
    }
  level = std::move(merged);
}

}  // namespace

Arrangement build_arrangement(const structure::PolycubeStructure& s, const TetLocator& locator,
                              double tol, long long max_boxes, const std::array<std::vector<double>, 3>& extra) {
  Arrangement arr;
  arr.tolerance = tol;
  arr.chart_level.assign(s.charts.size(), -1);
  for (int a = 0; a < 3; ++a) {
    // cluster the chart coordinates of this axis: a gap larger than tol starts a new level
    std::vector<std::pair<double, int>> coords;
    for (std::size_t c = 0; c < s.charts.size(); ++c)
      if (s.charts[c].axis == a) coords.emplace_back(s.charts[c].coordinate, static_cast<int>(c));
    std::sort(coords.begin(), coords.end());
    for (std::size_t i = 0; i < coords.size();) {
      std::size_t j = i + 1;
      while (j < coords.size() && coords[j].first - coords[j - 1].first <= tol) ++j;
      double sum = 0.0;
      for (std::size_t k = i; k < j; ++k) {
        sum += coords[k].first;
        arr.chart_level[static_cast<std::size_t>(coords[k].second)] =
            static_cast<int>(arr.level[a].size());
      }
      arr.level[a].push_back(sum / static_cast<double>(j - i));
      i = j;
    }
    if (arr.level[a].size() < 2)
      throw core::InputError(
          fmt::format("the polycube has {} chart plane(s) along {}: not a closed polycube",
                      arr.level[a].size(), core::axis_name(a)));
    add_extra_levels(arr.level[a], extra[static_cast<std::size_t>(a)], tol, a, s, arr.chart_level);
  }
  const long long nbox = static_cast<long long>(arr.boxes(0)) * arr.boxes(1) * arr.boxes(2);
  if (nbox > max_boxes)
    throw core::InputError(
        fmt::format("the polycube has {} x {} x {} distinct chart planes: too many to grid",
                    arr.level[0].size(), arr.level[1].size(), arr.level[2].size()));
  // a box of the arrangement is inside when its centre is (no chart crosses a box)
  arr.inside.assign(static_cast<std::size_t>(nbox), 0);
  for (int k = 0; k < arr.boxes(2); ++k)
    for (int j = 0; j < arr.boxes(1); ++j)
      for (int i = 0; i < arr.boxes(0); ++i) {
        const core::Vec3 c(0.5 * (arr.level[0][i] + arr.level[0][i + 1]),
                           0.5 * (arr.level[1][j] + arr.level[1][j + 1]),
                           0.5 * (arr.level[2][k] + arr.level[2][k + 1]));
        arr.inside[arr.box_index(i, j, k)] = locator.locate(c).tet >= 0 ? 1 : 0;
      }
  return arr;
}

}  // namespace polycube::mesh
