#pragma once
//! \file cut_planes.h
//! \brief The model-space plane of every cut of the plan (thesis §6.3, adapted to the cut tree).
//!
//! The thesis flattens each box side separately (a queue of sides, each pivoting on the edges of
//! sides flattened before it) because its parts are built side by side. Here a cut splits a whole
//! piece of the solid at once, so each cut needs one plane: the least-squares plane of the
//! mapped grid vertices of all the contacts across it (a cut without contacts, between boxes
//! that do not touch: of the polycube's whole section by its plane). The edges and corners of the
//! parts are then the exact intersections of these planes, shared by the parts that meet there, so
//! no pivoting is needed to keep neighbouring sides consistent.
//!
//! One plane for a whole cut can miss a small box: where the map's interface curves between
//! contact patches, the least-squares plane may pass beyond a box near it, and the box's part
//! comes out empty. So the fit keeps every box of the cut's group on its own side: the mapped
//! centre of each box and its corners shrunk halfway towards that centre must lie on the side
//! of the box (a convex least-squares problem in the plane's tilt and offset, solved exactly).
//! Since every cut on the way down to a box keeps its centre on the box's side, each part holds
//! its box's mapped centre: no part can come out empty.

#include "core/polycube_map.h"
#include "fabricate/corners.h"
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
  //! Tilted away from the least-squares plane to keep every box on its side (see above); 2 when
  //! only the box centres could be kept (the shrunk corners could not all be)
  int constrained = 0;
  int unkept_boxes = 0;  //!< boxes whose mapped centre no plane could keep on its side
};

//! The plane of one cut of a partition's boxes (a separation, axis -1: none).
CutPlane fit_cut_plane(const ToModel& to_model, const OccupancyGrid& grid,
                       const BoxPartition& partition, const Cut& cut);

//! One plane per cut of the plan (same order); a separation (axis -1) gets none (points 0).
//! \param tolerance distance within which a point counts as inside a tet, relative to the
//!        polycube's bounding-box diagonal
std::vector<CutPlane> fit_cut_planes(const core::PolycubeMap& map, const OccupancyGrid& grid,
                                     const CutPlan& plan, double tolerance = 1e-6);

}  // namespace polycube::fabricate
