#pragma once
//! \file milling.h
//! \brief Whether a part can be milled with a 3-axis or a 4-axis machine (thesis §6.5.2,
//! §6.5.3, Table 6.2 columns %3AM and %4AM).
//!
//! A part is a closed, outward-oriented triangle surface. A triangle is judged at one sample,
//! its barycentre (the thesis's approximation, §6.5.3), and counts with its whole area.
//! Fractions are over the part's whole surface area, the base included. Degenerate
//! (zero-area) triangles carry no area and are reported reachable and reached.
//!
//! **Reaching a triangle.** The tool travelling along a direction `d` (coming from the `-d`
//! side) reaches a triangle when
//!  1. the triangle does not turn away from it: `n . d <= 1e-9` for the unit outward normal `n`.
//!     Faces exactly side-on (`n . d = 0`) count as reachable, milled by the flank of the tool:
//!     this is the height-field test of §6.5.2, which accepts vertical faces (`n . up >= 0`);
//!  2. the segment from outside the part to the sample hits no triangle. The sample is the
//!     barycentre lifted off the surface by 1e-5 of the part's bounding-box diagonal along `n`.
//!     So a ray along a face it grazes (a vertical side seen from above, an end face seen from a
//!     tool orthogonal to the axis) runs just outside that face and beside the edges of its
//!     neighbours instead of through them, and the triangle never hides itself (its plane is met
//!     behind the sample); anything else in the way, however thin the contact, blocks it.
//!
//! Rays are cast with Embree in single precision after centring the part on its bounding box
//! (relative error about 1e-7 of the diagonal, well below the lift). Results are deterministic:
//! one thread builds the tree and casts the rays, in triangle order.

#include "core/types.h"

#include <cstdint>
#include <vector>

namespace polycube::fabricate {

//! 3-axis milling with the stock standing on a base (thesis §6.5.2): the tool comes from above,
//! from `-down`, and travels along `down`.
struct ThreeAxis {
  static constexpr std::uint8_t kReachable = 0;   //!< faces up or side-on, nothing above it
  static constexpr std::uint8_t kTurnedAway = 1;  //!< faces down: not a height field there
  static constexpr std::uint8_t kOccluded = 2;    //!< faces up or side-on, under another part
  static constexpr std::uint8_t kBase = 3;        //!< on the table, not checked

  //! Area fraction of triangles turned away from the tool (`n . up < -1e-9`), the base
  //! excluded: the thesis's height-field test.
  double height_field_unreachable = 0;
  //! Area fraction turned towards the tool (or side-on) but hidden under another part of the
  //! surface: the ray from above to its sample hits the surface first. Beyond the thesis, whose
  //! test sees only normals.
  double occluded = 0;
  //! The two together: the part's %3AM on this base.
  double unreachable = 0;
  //! #T per triangle: kReachable, kTurnedAway, kOccluded or kBase.
  std::vector<std::uint8_t> triangle;
};

//! Check 3-axis milling of a part standing on a base.
//! \param part            closed, outward triangle surface
//! \param down            outward normal of the base (the side on the table); normalised here
//! \param base_triangles  triangles of the base side: marked kBase, not checked
//! \pre `down` is not zero and `base_triangles` index triangles of `part`
ThreeAxis three_axis(const core::TriMesh& part, const core::Vec3& down,
                     const std::vector<int>& base_triangles);

//! The rotation axis of a 4-axis machine: a point on it and its unit direction.
struct Axis {
  core::Vec3 point = core::Vec3::Zero();
  core::Vec3 direction = core::Vec3::UnitZ();
};

//! 4-axis milling about an axis (thesis §6.5.3).
struct FourAxis {
  Axis axis;  //!< the axis used (direction normalised)
  //! Area fraction reached from no tool direction: the part's %4AM.
  double unreached = 0;
  //! #T per triangle: 1 when some tool direction reaches it, 0 never.
  std::vector<std::uint8_t> reached;
};

//! Check 4-axis milling of a part rotating about `axis`.
//!
//! The tool directions are `directions` unit vectors evenly spaced in the plane orthogonal to
//! the axis (the thesis uses 40 over [0, 2π)), the first along the coordinate axis least aligned
//! with the axis, projected on that plane. Faces orthogonal to the axis (the two ends of a
//! block turning about its length) are side-on to every direction: by the rule in this file's
//! header they are reached unless something stands beside them in their own plane, as in the
//! thesis, whose Table 6.2 reports almost no unreached area on parts with flat sides across
//! their axis. Only the axis's direction matters to visibility: the tool comes from outside
//! the part whatever the point (tool length is not modelled, as in the thesis).
//! \param part        closed, outward triangle surface
//! \param axis        rotation axis; `direction` is normalised here
//! \param directions  number of tool directions, >= 1
//! \pre `axis.direction` is not zero, `directions >= 1`
FourAxis four_axis(const core::TriMesh& part, const Axis& axis, int directions = 40);

//! An automatic rotation axis for four_axis, through the part's area-weighted centroid.
//!
//! The thesis suggests the orientation that best aligns the face normals with the axes (after
//! [MLS*18]) and leaves the final choice to the user. Here the candidates are the three
//! principal directions of the area-weighted normal covariance `sum_t A_t n_t n_t^T`: the
//! directions the normals align with best, which include the normal of a large flat side. An
//! axis orthogonal to most normals lets the tool face them, so the candidates are tried from
//! the smallest eigenvalue up, and the first one leaving the least unreached area (four_axis
//! with `directions`) wins. Deterministic; the direction's largest component is positive.
//! \param part        closed, outward triangle surface
//! \param directions  number of tool directions of the trial checks, >= 1
Axis choose_axis(const core::TriMesh& part, int directions = 40);

}  // namespace polycube::fabricate
