#pragma once
//! \file exact_geometry.h
//! \brief Checks of the tests that need CGAL's exact predicates or its AABB tree, compiled once
//! in polycube_test_exact (tests/support/CMakeLists.txt).
#include "core/types.h"

#include <vector>

namespace polycube::test {

//! True when the triangle mesh intersects itself (CGAL's does_self_intersect, exact
//! predicates). Throws std::runtime_error when its triangles do not form a halfedge structure.
bool self_intersects(const core::TriMesh& m);

//! Largest distance from the points to the surface (CGAL's AABB tree, exact closest points).
double farthest_from(const std::vector<core::Vec3>& points, const core::TriMesh& surface);

}  // namespace polycube::test
