#pragma once
//! \file cut_planes.h
//! \brief The model-space plane of every cut of the plan (thesis §6.3, adapted to the cut tree).
//!
//! The thesis flattens each box side separately (a queue of sides, each pivoting on the edges of
//! sides flattened before it) because its parts are built side by side. Here a cut splits a whole
//! piece of the solid at once, so each cut needs one plane: the least-squares plane of the
//! mapped grid vertices of all the contacts across it. The edges and corners of the parts are
//! then the exact intersections of these planes, shared by the parts that meet there, so no
//! pivoting is needed to keep neighbouring sides consistent.

#include "core/polycube_map.h"
#include "fabricate/cut_plan.h"

#include <vector>

namespace polycube::fabricate {

//! The plane n . x = offset, n a unit vector pointing from the cut's below side to its above side.
struct CutPlane {
  core::Vec3 normal = core::Vec3::UnitX();
  double offset = 0.0;
  int points = 0;              //!< mapped grid vertices fitted
  double max_deviation = 0.0;  //!< largest distance of those points from the plane (model units)
  double rms_deviation = 0.0;  //!< root mean square of the distances
};

//! One plane per cut of the plan (same order); a separation (axis -1) gets none (points 0).
//! \param tolerance polycube-space distance within which a point counts as inside a tet
std::vector<CutPlane> fit_cut_planes(const core::PolycubeMap& map, const OccupancyGrid& grid,
                                     const CutPlan& plan, double tolerance = 1e-6);

}  // namespace polycube::fabricate
