#pragma once
//! \file mesh_io.h
//! \brief Reading and writing mesh files, format chosen by extension (ARCHITECTURE §5).
//!
//! Surfaces: .obj .off .stl (ASCII and binary) .ply (ASCII and binary little-endian).
//! Volumes:  .mesh (MEDIT) .vtk (legacy ASCII 3.0) .msh (Gmsh 4.1 ASCII).
//! Every reader throws core::InputError with "file:line: what" on bad input; every writer is
//! atomic (temporary file in the same folder, then rename), so a failed write leaves nothing.

#include "core/types.h"

#include <filesystem>
#include <string>
#include <vector>

namespace polycube::io {

enum class Format { Obj, Off, Stl, Ply, Medit, Vtk, Msh };

//! Options for writers whose format has variants.
struct WriteOptions {
  bool binary = false;  //!< STL and PLY: write binary (little-endian) instead of ASCII
};

//! Format from a file name's extension (case-insensitive). \throw core::InputError if unknown.
Format format_from_path(const std::filesystem::path& path);

//! Short name of a format ("obj", "mesh", ...).
const char* format_name(Format f);

//! True when the format can hold volume elements (tets/hexes).
bool is_volume_format(Format f);

//! Read any supported file. \throw core::InputError naming the file (and line) on bad input.
core::MeshData read_mesh(const std::filesystem::path& path);

//! Write any supported file atomically.
//! \throw core::InputError if the data cannot be stored in that format (e.g. tets to .obj),
//!        core::Error on I/O failure (nothing is left behind).
void write_mesh(const std::filesystem::path& path, const core::MeshData& data,
                const WriteOptions& options = {});

//! Read a file and return its triangles (quads split into two triangles) as a surface.
//! \throw core::InputError when the file holds no surface elements.
core::TriMesh read_surface(const std::filesystem::path& path);

//! Write text to a file atomically (used for reports and labelings too).
void write_text_atomic(const std::filesystem::path& path, const std::string& text);

}  // namespace polycube::io
