#pragma once
//! \file certifier.h
//! \brief Independent certifier of polycube maps for the tests: exact orientation predicates
//! (CGAL), its own boundary extraction, bit-exact chart planes and exact facing; shares no code
//! with construct/certify. Compiled once, in polycube_test_exact (tests/support/CMakeLists.txt),
//! so that the tests that use it do not each parse CGAL.
#include "core/types.h"

#include <vector>

namespace polycube::test {

struct Verdict {
  int bad_model = 0, bad_polycube = 0, off_plane = 0, unlabeled = 0, boundary_faces = 0, wrong_facing = 0;
};

//! The verdict on a map: `tets` over `model` and `poly` points, the boundary triangles `tris`
//! with their labels (2 * axis + (0 for +, 1 for -)).
Verdict independent_check(const std::vector<core::Tet>& tets, const std::vector<core::Vec3>& model,
                          const std::vector<core::Vec3>& poly, const std::vector<core::Tri>& tris,
                          const std::vector<int>& labels);

//! True when the verdict accepts the map.
bool certified(const Verdict& v);

}  // namespace polycube::test
