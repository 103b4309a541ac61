#pragma once
//! \file structure_io.h
//! \brief Writing a polycube structure for viewing (legacy VTK 3.0 ASCII unstructured grid).

#include "structure/structure.h"

#include <filesystem>
#include <string>
#include <vector>

namespace polycube::structure {

//! The structure as a legacy VTK "3.0" ASCII UNSTRUCTURED_GRID: the boundary triangles (cell
//! type 5), every mesh segment of every polycube edge (line cells, type 3) and every corner
//! (vertex cells, type 1), with cell data (FIELD arrays) `kind` (0 triangle, 1 edge segment, 2
//! corner), `id` (chart, edge or corner id), `axis` (chart normal axis or edge axis, -1 for
//! corners), `label` (chart label 0..5, -1 otherwise) and `concave` (1 for segments of concave
//! edges, 0 otherwise). Only the map vertices used are written. \param positions #V positions to
//! draw at (the map's polycube or model positions)
std::string structure_to_vtk(const PolycubeStructure& s, const std::vector<core::Vec3>& positions);

//! Write structure_to_vtk atomically.
void write_structure_vtk(const std::filesystem::path& path, const PolycubeStructure& s,
                         const std::vector<core::Vec3>& positions);

}  // namespace polycube::structure
