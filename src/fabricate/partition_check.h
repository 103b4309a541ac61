#pragma once
//! \file partition_check.h
//! \brief Independent checks that parts partition their solid (for tests and benchmarks): the
//! construction guarantees it (parts.h), this measures it from the finished, rounded parts.
//!
//! Overlap and gap are estimated on a grid of sample points over the solid's bounding box
//! (shifted by irrational fractions of a step, so no sample lies on an axis-aligned cut face): a
//! sample inside the solid should be inside exactly one part. The surface deviation is the
//! largest distance from the parts' own triangles (those not on a cut plane) to the solid's
//! surface, attained at sample points of those triangles (vertices, centroids, refinements).

#include "core/types.h"
#include "fabricate/parts.h"

namespace polycube::fabricate {

struct PartitionCheck {
  int samples_inside = 0;        //!< samples inside the solid
  double overlap = 0.0;          //!< fraction of those inside two parts or more
  double gap = 0.0;              //!< fraction of those inside no part
  double surface_deviation = 0;  //!< distance of non-cut triangles to the solid / its diagonal
};

//! \param samples_per_axis samples along the bounding box's longest side (others in proportion)
PartitionCheck check_partition(const Parts& parts, const core::TriMesh& solid,
                               int samples_per_axis = 48);

}  // namespace polycube::fabricate
