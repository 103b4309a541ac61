#pragma once
//! \file parts_output.h
//! \brief The files of a decomposition into parts (thesis ch. 6), written into one folder:
//!   part_NN.stl       one binary STL per part, in place (model units)
//!   parts.3mf         the assembly: one object per part, in place, each with its colour
//!   exploded.ply      the parts moved apart from the solid's centre, a colour per part
//!                     (face properties red, green, blue) and the part id (MeshLab, ParaView)
//!   exploded.vtk      the same with cell data part_id and flat_side (1 on a cut face; ParaView)
//!   parts.json        the decomposition and, per part, its box, volume, bounding box,
//!                     triangles, checks and flat sides (outward normal, area), and its base
//! and the same table as text for the terminal.

#include "fabricate/decompose.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace polycube::pipeline {

//! Why a part fails the checks (closed, outward, free of self-intersections, not empty), or
//! "" when it passes.
std::string part_problem(const fabricate::Part& part);

//! Parts failing the checks.
int failing_parts(const fabricate::Decomposition& d);

//! \throw core::GeometryError when a part fails its checks, or does not fit the chamber on any
//!        of its flat sides, naming the first and the remedy
void check_parts(const fabricate::Decomposition& d, const fabricate::DecomposeOptions& o);

//! The decomposition as JSON (parts.json's content).
nlohmann::json parts_json(const fabricate::Decomposition& d, const fabricate::DecomposeOptions& o);

//! The table printed on the terminal: one line per part.
std::string parts_table(const fabricate::Decomposition& d);

//! Write every file above into `dir` (created); returns the paths written, in order. Empty parts
//! have no STL and are left out of the 3MF and the exploded views.
std::vector<std::filesystem::path> write_parts(const std::filesystem::path& dir,
                                               const fabricate::Decomposition& d,
                                               const fabricate::DecomposeOptions& o);

}  // namespace polycube::pipeline
