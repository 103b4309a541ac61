#pragma once
//! \file geometry_repairs.h
//! \brief The repairs of repair.h built on CGAL: orientation that bounds a volume, hole filling,
//! alpha wrapping. Internal to the repair module.

#include "core/types.h"
#include "repair/repair.h"

namespace polycube::repair::detail {

//! The centre of triangle `t`: where a report places a repair of it.
inline core::Vec3 centre(const std::vector<core::Vec3>& points, const core::Tri& t) {
  return (points[t[0]] + points[t[1]] + points[t[2]]) / 3.0;
}

//! Turn the triangles of a manifold, orientable surface so that they are consistent and, where
//! closed, bound a volume (nested shells alternate); the triangles turned are counted, and the
//! first placed, in `report`.
void orient_to_bound_volume(core::TriMesh& mesh, RepairReport& report);

//! Close the holes of at most `max_edges` boundary edges with refined, faired patches.
void fill_holes(core::TriMesh& mesh, int max_edges, RepairReport& report);

//! Replace the surface by its alpha wrap (alpha and offset in model units).
void alpha_wrap(core::TriMesh& mesh, double alpha, double offset, RepairReport& report);

}  // namespace polycube::repair::detail
