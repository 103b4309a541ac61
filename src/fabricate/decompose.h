#pragma once
//! \file decompose.h
//! \brief The whole decomposition of a solid into parts along its polycube map (thesis §6.2–6.4,
//! ARCHITECTURE §6.7), as one list of named steps: occupancy grid, box partition, merging,
//! cut plan, cut planes, exact cuts; with a chamber, the loop that splits the parts too large
//! to be made in one piece.
//!
//! The chamber loop. A part too large for the chamber in every orientation on its flat sides is
//! split by a plane through the middle of its box in polycube space, across the axis whose
//! mapped extent is largest, and the decomposition is made again with that plane forced; the
//! box it came from is never re-formed by merging. Merging itself only joins boxes whose
//! estimated part (the box's mapped lattice points) fits. Each round either splits a box or
//! forbids a union, so the loop ends; it stops after max_rounds and reports the parts that
//! still do not fit.

#include "core/polycube_map.h"
#include "core/types.h"
#include "fabricate/box_partition.h"
#include "fabricate/chamber.h"
#include "fabricate/cut_plan.h"
#include "fabricate/cut_planes.h"
#include "fabricate/parts.h"

#include <vector>

namespace polycube::fabricate {

struct DecomposeOptions {
  bool merge = true;    //!< join boxes whose union is a box (false: the thesis's partition)
  Chamber chamber;      //!< not limited: no splitting for size
  int max_rounds = 32;  //!< chamber rounds before giving up on the parts that still do not fit
};

struct Decomposition {
  OccupancyGrid grid;  //!< the polycube's grid, with the planes the chamber added
  int boxes = 0;       //!< boxes of the thesis's partition (before chamber splits and merging)
  CutPlan plan;
  std::vector<CutPlane> planes;
  Parts parts;
  //! Per part: the index of the flat side it stands on in the chamber (its largest fitting
  //! side; 0 when the chamber is not limited), -1 when it fits on none or has no flat side.
  std::vector<int> base;
  int rounds = 1;          //!< decompositions made (more than 1 when the chamber split parts)
  int chamber_planes = 0;  //!< planes the chamber added to the grid
  int unfit_parts = 0;     //!< parts that fit the chamber on none of their sides
  double partition_seconds = 0.0;  //!< grid, partition, merging, plan and planes (last round)
  double cut_seconds = 0.0;        //!< the exact cuts (last round)
  double seconds = 0.0;            //!< everything, all rounds
};

//! Cut `solid` (closed, outward, free of self-intersections: the map's model boundary or the
//! input surface) into parts along the map's boxes.
//! \throw core::InputError when the polycube cannot be partitioned or the solid is not closed
Decomposition decompose(const core::PolycubeMap& map, const core::TriMesh& solid,
                        const DecomposeOptions& options = {});

}  // namespace polycube::fabricate
