//! Guillotine cut plan of a box partition (see cut_plan.h).
#include "fabricate/cut_plan.h"

#include "core/disjoint_sets.h"
#include "core/errors.h"

#include <algorithm>
#include <limits>

namespace polycube::fabricate {

namespace {

//! A plane (axis, index) of the grid and how it relates to a group of boxes.
struct Candidate {
  int axis = 0, plane = 0;
  int crossed = 0;    //!< boxes of the group it crosses
  double area = 0.0;  //!< contact area across it between the group's boxes
};

double contact_area(const OccupancyGrid& g, const Contact& c) {
  double a = 1.0;
  for (int e = 0; e < 3; ++e)
    if (e != c.axis) a *= g.planes[e][c.hi[e]] - g.planes[e][c.lo[e]];
  return a;
}

//! Every plane strictly inside the group's extent on some axis, with the boxes it crosses and
//! the contact area across it.
std::vector<Candidate> candidates(const OccupancyGrid& g, const BoxPartition& p,
                                  const std::vector<int>& group) {
  std::vector<char> member(p.boxes.size(), 0);
  for (int b : group) member[b] = 1;
  std::vector<Candidate> out;
  for (int a = 0; a < 3; ++a) {
    int lo = std::numeric_limits<int>::max(), hi = std::numeric_limits<int>::min();
    for (int b : group) {
      lo = std::min(lo, p.boxes[b].lo[a]);
      hi = std::max(hi, p.boxes[b].hi[a]);
    }
    for (int plane = lo + 1; plane < hi; ++plane) {
      Candidate c{a, plane, 0, 0.0};
      bool boundary = false;  // some box of the group starts or ends here
      for (int b : group) {
        const Box& x = p.boxes[b];
        c.crossed += (x.lo[a] < plane && plane < x.hi[a]) ? 1 : 0;
        boundary = boundary || x.lo[a] == plane || x.hi[a] == plane;
      }
      if (!boundary) continue;
      for (const Contact& k : p.contacts)
        if (k.axis == a && k.plane == plane && member[k.boxes[0]] && member[k.boxes[1]])
          c.area += contact_area(g, k);
      out.push_back(c);
    }
  }
  return out;
}

//! Split every box of the group that the plane crosses into its two halves (new ids at the end;
//! the earlier cuts list the new half on the side of the box it came from).
int split_crossed(BoxPartition& p, std::vector<Cut>& cuts, std::vector<int>& group, int axis,
                  int plane) {
  int split = 0;
  const std::size_t n = group.size();
  for (std::size_t i = 0; i < n; ++i) {
    Box& x = p.boxes[group[i]];
    if (!(x.lo[axis] < plane && plane < x.hi[axis])) continue;
    Box upper = x;
    upper.lo[axis] = plane;
    x.hi[axis] = plane;
    p.boxes.push_back(upper);
    const int id = static_cast<int>(p.boxes.size()) - 1;
    group.push_back(id);
    for (Cut& c : cuts)
      for (auto* side : {&c.below, &c.above})
        if (std::find(side->begin(), side->end(), group[i]) != side->end()) side->push_back(id);
    ++split;
  }
  return split;
}

//! When the group's boxes do not all touch: the separation of the part holding its lowest box
//! from the rest.
bool separate(const BoxPartition& p, const std::vector<int>& group, Cut& cut) {
  std::vector<int> slot(p.boxes.size(), -1);
  for (std::size_t i = 0; i < group.size(); ++i) slot[group[i]] = static_cast<int>(i);
  core::DisjointSets ds(group.size());
  for (const Contact& k : p.contacts)
    if (slot[k.boxes[0]] >= 0 && slot[k.boxes[1]] >= 0)
      ds.unite(slot[k.boxes[0]], slot[k.boxes[1]]);
  const int first = ds.find(slot[*std::min_element(group.begin(), group.end())]);
  cut.axis = -1;
  cut.below.clear();
  cut.above.clear();
  for (int b : group) (ds.find(slot[b]) == first ? cut.below : cut.above).push_back(b);
  std::sort(cut.below.begin(), cut.below.end());
  std::sort(cut.above.begin(), cut.above.end());
  return !cut.above.empty();
}

void plan_group(const OccupancyGrid& g, CutPlan& plan, std::vector<int> group, int parent,
                bool parent_above) {
  if (group.size() < 2) return;
  std::vector<Candidate> cand = candidates(g, plan.partition, group);
  // Free planes first, largest seam first; else the plane crossing fewest boxes.
  const auto better = [](const Candidate& x, const Candidate& y) {
    if (x.crossed != y.crossed) return x.crossed < y.crossed;
    if (x.area != y.area) return x.area > y.area;
    return std::make_pair(x.axis, x.plane) < std::make_pair(y.axis, y.plane);
  };
  // A group whose boxes do not touch is cut too when a free plane lies between them (the arms
  // of a U): in model space the cuts above it may have left its pieces joined by a sliver, which
  // a separation by components would hand whole to one side. Without a free plane, it is
  // separated into its connected parts.
  Cut apart;
  apart.parent = parent;
  apart.parent_above = parent_above;
  const bool free_plane =
      !cand.empty() && std::min_element(cand.begin(), cand.end(), better)->crossed == 0;
  if (!free_plane && separate(plan.partition, group, apart)) {
    const int id = static_cast<int>(plan.cuts.size());
    plan.cuts.push_back(apart);
    plan_group(g, plan, apart.below, id, false);
    plan_group(g, plan, apart.above, id, true);
    return;
  }
  if (cand.empty())
    throw core::InputError("cut plan: a group of several boxes has no plane between them");
  const Candidate best = *std::min_element(cand.begin(), cand.end(), better);
  if (best.crossed > 0) {
    plan.split_boxes += split_crossed(plan.partition, plan.cuts, group, best.axis, best.plane);
    index_boxes(g, plan.partition);
  }
  Cut cut;
  cut.axis = best.axis;
  cut.plane = best.plane;
  cut.parent = parent;
  cut.parent_above = parent_above;
  std::sort(group.begin(), group.end());
  for (int b : group)
    (plan.partition.boxes[b].hi[best.axis] <= best.plane ? cut.below : cut.above).push_back(b);
  std::vector<char> below(plan.partition.boxes.size(), 0), above(plan.partition.boxes.size(), 0);
  for (int b : cut.below) below[b] = 1;
  for (int b : cut.above) above[b] = 1;
  for (const Contact& k : plan.partition.contacts)
    if (k.axis == best.axis && k.plane == best.plane && below[k.boxes[0]] && above[k.boxes[1]])
      cut.contacts.push_back(k);
  const int id = static_cast<int>(plan.cuts.size());
  plan.cuts.push_back(cut);
  const std::vector<int> lower = cut.below, upper = cut.above;
  plan_group(g, plan, lower, id, false);
  plan_group(g, plan, upper, id, true);
}

}  // namespace

CutPlan plan_cuts(const OccupancyGrid& grid, const BoxPartition& partition) {
  CutPlan plan;
  plan.partition = partition;
  std::vector<int> all(partition.boxes.size());
  for (std::size_t b = 0; b < all.size(); ++b) all[b] = static_cast<int>(b);
  plan_group(grid, plan, all, -1, false);
  return plan;
}

}  // namespace polycube::fabricate
