#pragma once
//! \file parts_output.h
//! \brief The files of a decomposition into parts (thesis ch. 6), written into one folder:
//!   part_NN.stl       one binary STL per part, in place (model units)
//!   print/part_NN.stl the part standing on its best base on the bed (z = 0), ready to slice
//!   parts.3mf         the assembly: one object per part, in place, each with its colour
//!   exploded.ply      the parts moved apart from the solid's centre, a colour per part
//!                     (face properties red, green, blue) and the part id (MeshLab, ParaView)
//!   exploded.vtk      the same with cell data part_id, flat_side (1 on a cut face) and
//!                     overhang (where the part on its best base needs support: 1 an
//!                     overhanging face, 2 along a keel or at a tip; ParaView)
//!   parts.json        the decomposition and, per part, its box, volume, bounding box,
//!                     triangles, checks, flat sides (outward normal, area, support needed
//!                     standing on it), and its best base; the thesis's Table 6.2 figures
//! and the same table as text for the terminal.

#include "fabricate/decompose.h"
#include "fabricate/milling.h"
#include "fabricate/printing.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace polycube::pipeline {

//! How to check milling (thesis §6.5.2-6.5.3).
struct MillOptions {
  int directions = 40;                  //!< 4-axis tool directions about the axis
  std::optional<fabricate::Axis> axis;  //!< the 4-axis rotation axis; empty: chosen per part
};

//! A part milled: 3-axis on each flat side as the stock's base, the best; 4-axis about an axis.
struct PartMill {
  std::vector<double> three_axis;        //!< per flat side: unreachable area fraction (%3AM / 100)
  int best = -1;                         //!< side with the least unreachable area; -1: no flat side
  fabricate::ThreeAxis best_three_axis;  //!< on the best side (per-triangle classes)
  fabricate::FourAxis four_axis;
};

//! 3-axis on every flat side of the part (the stock on it, the tool from the other side), the
//! best side, and 4-axis about the given axis or the part's chosen one.
PartMill mill_part(const fabricate::Part& part, const MillOptions& options);

//! A decomposition with the checks of how its parts can be made (issue 21).
struct Fabrication {
  fabricate::Decomposition decomposition;
  fabricate::DecomposeOptions options;
  fabricate::PrintOptions print;
  std::vector<fabricate::PartPrint> prints;  //!< per part: support on each flat side, the best
  fabricate::Standing whole;  //!< the solid printed in one piece on its best axis (%3DPST)
  MillOptions mill;
  std::vector<PartMill> mills;  //!< per part
  double check_seconds = 0.0;

  //! Support fraction of the parts on their best bases, area-weighted (%3DPPST / 100).
  [[nodiscard]] double parts_support_fraction() const;
  //! Area fractions of the parts not reached in 3-axis (best sides) / 4-axis, area-weighted.
  [[nodiscard]] double parts_three_axis_fraction() const;
  [[nodiscard]] double parts_four_axis_fraction() const;
};

//! Decompose the solid and run the checks on its parts.
Fabrication fabricate_solid(const core::PolycubeMap& map, const core::TriMesh& solid,
                            const fabricate::DecomposeOptions& options,
                            const fabricate::PrintOptions& print = {},
                            const MillOptions& mill = {});

//! The support a part needs standing so, for parts.json and check-fab's JSON: support_percent
//! (the thesis's area), needs_support, keels, keel_length, tips.
nlohmann::json support_json(const fabricate::Standing& s);

//! Why a part fails the checks (closed, outward, free of self-intersections, not empty), or
//! "" when it passes.
std::string part_problem(const fabricate::Part& part);

//! Parts failing the checks.
int failing_parts(const fabricate::Decomposition& d);

//! \throw core::GeometryError when a part fails its checks, or does not fit the chamber on any
//!        of its flat sides, naming the first and the remedy
void check_parts(const Fabrication& f);

//! The decomposition and its checks as JSON (parts.json's content).
nlohmann::json parts_json(const Fabrication& f);

//! The table printed on the terminal: one line per part, then the whole model's figures.
std::string parts_table(const Fabrication& f);

//! Remove the files write_parts writes (part_NN.stl, print/part_NN.stl, parts.3mf,
//! exploded.*, parts.json) from `dir`, and nothing else. Returns how many were removed.
int remove_earlier_parts(const std::filesystem::path& dir);

//! Write every file above into `dir` (created; the files of an earlier decomposition there are
//! removed first); returns the paths written, in order. Empty parts have no STL and are left
//! out of the 3MF and the exploded views.
std::vector<std::filesystem::path> write_parts(const std::filesystem::path& dir,
                                               const Fabrication& f);

}  // namespace polycube::pipeline
