#pragma once
//! \file cut_plan.h
//! \brief The order in which the solid is cut into parts (ARCHITECTURE §6.7): a binary tree of
//! guillotine cuts in polycube space. Each cut splits a group of boxes by one polycube plane that
//! crosses none of them; in model space the piece of the solid holding that group is then split
//! by one plane fitted to the cut, so every point of the piece goes to exactly one side. Cutting
//! this way, no region can be claimed by two parts nor left to none: the parts are a partition
//! of the solid by construction.
//!
//! A set of boxes may admit no guillotine cut (a pinwheel); then the boxes crossed by the plane
//! that crosses fewest are split along it (more parts, never a gap).

#include "fabricate/box_partition.h"

#include <functional>
#include <vector>

namespace polycube::fabricate {

//! One guillotine cut of a group of boxes. A group whose boxes do not all touch and that no free
//! plane divides is instead separated into its connected parts: axis -1, no plane, since in
//! model space its piece is then in separate components. (Where a free plane exists, as between
//! the arms of a U once its base is cut off, the group is cut by it like any other: its cut has
//! no contacts.)
struct Cut {
  int axis = 0;                   //!< normal axis of the polycube plane; -1: a separation
  int plane = 0;                  //!< grid plane index along axis
  std::vector<int> below;         //!< boxes on the low side (ids of the plan's partition)
  std::vector<int> above;         //!< boxes on the high side
  std::vector<Contact> contacts;  //!< contacts across the plane between the two sides
  int parent = -1;                //!< the cut whose side this group is (-1: the whole polycube)
  bool parent_above = false;      //!< which side of the parent
};

//! The cuts, parents before children, and the boxes they end in.
struct CutPlan {
  BoxPartition partition;  //!< the input partition, with the boxes a pinwheel forced to split
  std::vector<Cut> cuts;
  int split_boxes = 0;  //!< boxes split because no guillotine cut existed
};

//! Whether a candidate cut of the partition's boxes is acceptable (decompose: its model-space
//! plane keeps every box of the group on its side).
using CutCheck = std::function<bool(const BoxPartition&, const Cut&)>;

//! Plan the cuts of a partition: at each group, the free plane with the largest contact area
//! between its sides (ties: lowest axis, then plane), so the largest seams are cut first; with a
//! check, the first free plane in that order that the check accepts (else the first).
CutPlan plan_cuts(const OccupancyGrid& grid, const BoxPartition& partition,
                  const CutCheck& check = nullptr);

}  // namespace polycube::fabricate
