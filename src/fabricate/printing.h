#pragma once
//! \file printing.h
//! \brief How much support a part needs when 3D printed on each of its flat sides (thesis
//! §6.5.1, Table 6.2).
//!
//! Printed standing on a base (a flat side on the bed, its outward normal pointing down), a
//! triangle overhangs when it faces down more steeply than the printer's angle: its normal
//! within `overhang_degrees` of straight down (45° by default: a surface tilted more than 45°
//! from the vertical). Triangles lying on the bed (the base, and any other down-facing triangle
//! at the bed's height) need none. The support fraction is the overhanging area over the part's
//! whole surface area.
//!
//! Beyond the thesis's area: a slicer also supports features that have no area. A keel (a convex
//! edge between two faces each steep enough, rising less steeply than the printer's angle) and a
//! tip pointing down (a vertex lower than its neighbours, the part above it) have nothing within
//! the printer's angle below them. A part with either needs support although its fraction is 0;
//! `Standing::needs_support()` says so.

#include "core/types.h"
#include "fabricate/chamber.h"
#include "fabricate/parts.h"

#include <cstdint>
#include <string>
#include <vector>

namespace polycube::fabricate {

struct PrintOptions {
  double overhang_degrees = 45.0;  //!< largest overhang printed without support, from vertical
  Chamber chamber;                 //!< bases on which the part does not fit are not chosen
};

//! Standing on one direction.
struct Standing {
  core::Vec3 down = -core::Vec3::UnitZ();  //!< outward normal of the base
  double overhang_area = 0.0;              //!< model units²
  double support_fraction = 0.0;           //!< overhang_area / the part's surface area
  bool fits = true;                        //!< fits the chamber standing so
  int keels = 0;                           //!< keel edges with nothing below (see keels_and_tips)
  double keel_length = 0.0;                //!< their length, model units
  int tips = 0;                            //!< tips pointing down above the bed

  //! Any support at all: overhanging area, a keel or a tip.
  [[nodiscard]] bool needs_support() const { return overhang_area > 0.0 || keels > 0 || tips > 0; }
};

//! Per-triangle overhang on a base: 1 overhanging, 0 not (bed triangles included).
std::vector<std::uint8_t> overhanging(const core::TriMesh& mesh, const core::Vec3& down,
                                      double overhang_degrees);

//! "3 keel edges (12.5 long), 1 tip pointing down" (only the kinds present; "" when none).
std::string describe_keels_and_tips(const Standing& s);

//! Features without area that need support on `down` (see the file comment).
struct KeelsAndTips {
  int keels = 0;
  double keel_length = 0.0;
  int tips = 0;
  std::vector<std::uint8_t> triangle;  //!< per triangle: 1 along a keel or at a tip
};
//! A keel is a convex edge, not on the bed, whose two faces do not overhang, yet no direction
//! within `overhang_degrees` of straight down enters the solid through both (the material under
//! it is beyond the printer's angle, on either side). A tip is a vertex above the bed lower than
//! all its neighbours, with the outward normals around it pointing down (the solid above it).
KeelsAndTips keels_and_tips(const core::TriMesh& mesh, const core::Vec3& down,
                            double overhang_degrees);

//! Per triangle, what to look at: 0 printable as it is, 1 overhanging, 2 along a keel or at a tip.
std::vector<std::uint8_t> support_marks(const core::TriMesh& mesh, const core::Vec3& down,
                                        double overhang_degrees);

//! The part on `down`: overhanging area and fraction, keels and tips.
Standing stand(const core::TriMesh& mesh, const core::Vec3& down, const PrintOptions& options);

//! A part on each of its flat sides, and the best: the least support among the sides it fits
//! the chamber on; ties: the shorter keels, then the fewer tips, then the larger side.
struct PartPrint {
  std::vector<Standing> sides;  //!< per flat side of the part, same order
  int best = -1;                //!< index into sides; -1 when it fits on none (or has none)
  double area = 0.0;            //!< the part's surface area
};
PartPrint check_part_printing(const Part& part, const PrintOptions& options);

//! The part turned to stand on `down` (its outward normal pointing to -z) with its lowest point at
//! z = 0 and its bounding box centred on the z axis: the file a slicer takes as it is. Turned by
//! the shortest rotation, so a part already standing upright only moves.
core::TriMesh stand_on_bed(const core::TriMesh& mesh, const core::Vec3& down);

//! A solid printed in one piece on the best of the six directions of its bounding box (the
//! thesis's %3DPST): the least support fraction.
Standing best_axis_standing(const core::TriMesh& solid, const PrintOptions& options);

}  // namespace polycube::fabricate
