#pragma once
//! \file chamber.h
//! \brief Does a part fit a printer's (or mill's) build volume? (thesis §6.4, §6.5.1)
//!
//! A part is made standing on one of its flat sides, so it fits when, for some side taken as the
//! base, its height above the base is within the chamber's height and its footprint on the bed
//! fits the chamber's width × depth after some turn about the vertical.

#include "core/types.h"

#include <vector>

namespace polycube::fabricate {

//! Build volume: x by y on the bed, z high (model units). All zero: no limit.
struct Chamber {
  double x = 0.0, y = 0.0, z = 0.0;
  [[nodiscard]] bool limited() const { return x > 0 && y > 0 && z > 0; }
};

//! Whether the points fit the chamber standing on a base whose outward normal is `down`.
//! The footprint is tried at every edge direction of its convex hull and every degree of turn.
bool fits_standing_on(const std::vector<core::Vec3>& points, const core::Vec3& down,
                      const Chamber& chamber);

//! The first of `bases` (outward normals) the points fit standing on, or -1. Always 0 when the
//! chamber is not limited and there is a base.
int fitting_base(const std::vector<core::Vec3>& points, const std::vector<core::Vec3>& bases,
                 const Chamber& chamber);

}  // namespace polycube::fabricate
