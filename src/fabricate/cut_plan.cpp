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

//! The cut of the group along the candidate's plane (boxes sorted on each side, the contacts
//! across it).
Cut make_cut(const BoxPartition& p, std::vector<int> group, const Candidate& c, int parent,
             bool parent_above) {
  Cut cut;
  cut.axis = c.axis;
  cut.plane = c.plane;
  cut.parent = parent;
  cut.parent_above = parent_above;
  std::sort(group.begin(), group.end());
  for (int b : group) (p.boxes[b].hi[c.axis] <= c.plane ? cut.below : cut.above).push_back(b);
  std::vector<char> below(p.boxes.size(), 0), above(p.boxes.size(), 0);
  for (int b : cut.below) below[b] = 1;
  for (int b : cut.above) above[b] = 1;
  for (const Contact& k : p.contacts)
    if (k.axis == c.axis && k.plane == c.plane && below[k.boxes[0]] && above[k.boxes[1]])
      cut.contacts.push_back(k);
  return cut;
}

void plan_group(const OccupancyGrid& g, CutPlan& plan, std::vector<int> group, int parent,
                bool parent_above, const CutCheck& check) {
  if (group.size() < 2) return;
  std::vector<Candidate> cand = candidates(g, plan.partition, group);
  // Free planes first, largest seam first; else the plane crossing fewest boxes.
  std::sort(cand.begin(), cand.end(), [](const Candidate& x, const Candidate& y) {
    if (x.crossed != y.crossed) return x.crossed < y.crossed;
    if (x.area != y.area) return x.area > y.area;
    return std::make_pair(x.axis, x.plane) < std::make_pair(y.axis, y.plane);
  });
  // A group whose boxes do not touch is cut too when a free plane lies between them (the arms
  // of a U): in model space the cuts above it may have left its pieces joined by a sliver, which
  // a separation by components would hand whole to one side. Without a free plane, it is
  // separated into its connected parts.
  Cut apart;
  apart.parent = parent;
  apart.parent_above = parent_above;
  const bool free_plane = !cand.empty() && cand.front().crossed == 0;
  if (!free_plane && separate(plan.partition, group, apart)) {
    const int id = static_cast<int>(plan.cuts.size());
    plan.cuts.push_back(apart);
    plan_group(g, plan, apart.below, id, false, check);
    plan_group(g, plan, apart.above, id, true, check);
    return;
  }
  if (cand.empty())
    throw core::InputError("cut plan: a group of several boxes has no plane between them");
  // The first free plane the check accepts (its model-space plane can keep every box on its
  // side), else the first.
  Candidate best = cand.front();
  if (check && free_plane)
    for (const Candidate& c : cand) {
      if (c.crossed > 0) break;
      if (check(plan.partition, make_cut(plan.partition, group, c, parent, parent_above))) {
        best = c;
        break;
      }
    }
  if (best.crossed > 0) {
    plan.split_boxes += split_crossed(plan.partition, plan.cuts, group, best.axis, best.plane);
    index_boxes(g, plan.partition);
  }
  const Cut cut = make_cut(plan.partition, group, best, parent, parent_above);
  const int id = static_cast<int>(plan.cuts.size());
  plan.cuts.push_back(cut);
  plan_group(g, plan, cut.below, id, false, check);
  plan_group(g, plan, cut.above, id, true, check);
}

}  // namespace

CutPlan plan_cuts(const OccupancyGrid& grid, const BoxPartition& partition, const CutCheck& check) {
  CutPlan plan;
  plan.partition = partition;
  std::vector<int> all(partition.boxes.size());
  for (std::size_t b = 0; b < all.size(); ++b) all[b] = static_cast<int>(b);
  plan_group(grid, plan, all, -1, false, check);
  return plan;
}

}  // namespace polycube::fabricate
