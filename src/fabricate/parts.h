#pragma once
//! \file parts.h
//! \brief The solid cut into parts along the cut plan (thesis §6.4, ARCHITECTURE §6.7).
//!
//! The cuts run in the plan's order on exact meshes (CGAL Surface_mesh over the exact kernel):
//! the piece of a group is clipped by the cut's plane once on each side, so its two halves
//! share the cut polygon exactly and every point of the piece goes to exactly one half; a
//! separation hands each connected component of the piece to the side whose boxes it maps
//! into. Coordinates are rounded to double only when a part is finished. The parts therefore
//! partition the solid: no region is claimed twice (the two halves of a cut are the two sides
//! of one plane) and none is lost (each half keeps everything on its side, stray components
//! included).

#include "core/polycube_map.h"
#include "core/types.h"
#include "fabricate/cut_plan.h"
#include "fabricate/cut_planes.h"

#include <functional>
#include <vector>

namespace polycube::fabricate {

//! A flat side of a part: where it lies on one of the cut planes.
struct FlatSide {
  int cut = -1;                             //!< the cut of the plan whose plane it lies on
  core::Vec3 normal = core::Vec3::UnitX();  //!< outward unit normal
  double area = 0.0;                        //!< model units²
};

//! One part: the solid's piece of one box.
struct Part {
  int box = -1;                   //!< box of the plan's partition
  core::TriMesh mesh;             //!< closed surface, outward (rounded from the exact construction)
  int components = 0;             //!< connected components (1 unless a cut left a stray piece)
  double volume = 0.0;            //!< enclosed volume (model units³)
  bool closed = false;            //!< no border edge
  bool outward = false;           //!< bounds a positive volume
  bool self_intersecting = true;  //!< checked with exact predicates after rounding
  std::vector<FlatSide> sides;    //!< its faces on cut planes, largest first
  std::vector<int> triangle_side;  //!< per triangle: index into sides, -1 on the solid's surface
};

//! All parts and what the checks found.
struct Parts {
  std::vector<Part> parts;
  double solid_volume = 0.0;
  double volume_sum = 0.0;
  int unassigned_components = 0;  //!< components of a separation no box claimed (sent below)
  int returned_strays = 0;        //!< stray components joined to the part whose box they map into
  double seconds = 0.0;
};

//! Box of the plan's partition that a model-space point maps into, or -1.
using BoxOf = std::function<int(const core::Vec3&)>;

//! BoxOf through the map: the point is located in a model-space tet (or the nearest one), taken
//! to polycube space with the same barycentric coordinates, and looked up in the grid.
BoxOf box_lookup(const core::PolycubeMap& map, const OccupancyGrid& grid,
                 const BoxPartition& partition, double tolerance = 1e-9);  // relative to the model's diagonal

//! Cut the solid (a closed, outward, self-intersection-free triangle surface) along the plan.
//! \param centres the mapped centre of every box of the plan's partition (model space)
//! \throw core::InputError when the solid is not a closed manifold surface
Parts cut_parts(const core::TriMesh& solid, const CutPlan& plan,
                const std::vector<CutPlane>& planes, const BoxOf& box_of,
                const std::vector<core::Vec3>& centres);

}  // namespace polycube::fabricate
