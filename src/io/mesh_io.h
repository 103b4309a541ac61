#pragma once
//! \file mesh_io.h
//! \brief Reading and writing mesh files, format chosen by extension (ARCHITECTURE §5).
//!
//! What each format holds (R = read, W = written; anything else is refused or dropped):
//!
//! | ext   | elements                        | labels              | fields      | notes                  |
//! |-------|---------------------------------|---------------------|-------------|------------------------|
//! | .obj  | tri, quad (polygons: fan)       | -                   | -           | v/vt/vn refs, neg. idx |
//! | .off  | tri, quad (polygons: fan)       | -                   | -           | COFF/NOFF/STOFF read   |
//! | .stl  | tri (quads split on write)      | -                   | -           | ASCII/binary, float    |
//! | .ply  | tri, quad (polygons: fan)       | -                   | point, cell | ASCII/binary LE (R BE) |
//! | .mesh | edge, tri, quad, tet, hex       | element + vertex    | -           | MEDIT, version 1..4 R  |
//! | .vtk  | tri, quad, tet, hex             | as "label" data     | point, cell | legacy ASCII 2.0-4.2 R |
//! | .msh  | edge, tri, quad, tet, hex       | physical tags       | -           | Gmsh 4.1 ASCII         |
//!
//! Vertex orders are those of core/elements.h in every format (they agree). Coordinates are
//! written in the shortest decimal form that reads back to the same double (STL: float).
//! Polygons of more than four vertices are fan-triangulated from their first vertex.
//! PLY fields are vertex and face properties; fields named red, green, blue (alpha) with
//! integer values in 0..255 are written as uchar, the colour convention of MeshLab and ParaView.
//! 3MF assemblies of parts have their own functions, in three_mf.h.
//! Writing refuses elements a format cannot hold (tets to .obj) with core::InputError before
//! any file is created, and drops attributes it cannot hold with a logged warning.
//!
//! Every reader throws core::InputError with one line "file:line: what" on bad input (empty,
//! truncated, garbage, NaN/Inf, index out of range, wrong counts, unsupported version or
//! element type); declared counts are checked against the file size before any allocation.
//! Every writer is atomic (temporary file in the same folder, then rename), so a failed write
//! leaves nothing behind.

#include "core/types.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace polycube::io {

enum class Format { Obj, Off, Stl, Ply, Medit, Vtk, Msh };

//! Options for writers whose format has variants.
struct WriteOptions {
  bool binary = false;  //!< STL and PLY: write binary (little-endian) instead of ASCII
  //! Binary PLY: coordinates and fields as double; by default they are float, which is what
  //! other tools write and all of them read (Gmsh 4.8 misreads double vertices).
  bool double_precision = false;
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
//! \throw core::InputError if the data cannot be stored in that format (e.g. tets to .obj) or
//!        the path cannot be written (missing folder, a directory, no permission), before any
//!        file is created; core::Error on a failure while writing (nothing is left behind).
void write_mesh(const std::filesystem::path& path, const core::MeshData& data,
                const WriteOptions& options = {});

//! Parse a file already in memory (fuzzing, tests, embedded data).
//! \param bytes the whole file content; \param name the name used in error messages.
//! \throw core::InputError "name:line: what" on bad input.
core::MeshData read_mesh_from_memory(std::string_view bytes, Format format, const std::string& name);

//! The content write_mesh would write, as a string (binary formats as raw bytes).
//! \param name the name used in error messages.
//! \throw core::InputError if the data cannot be stored in that format.
std::string write_mesh_to_string(const core::MeshData& data, Format format, const WriteOptions& options = {},
                                 const std::string& name = "<memory>");

//! Check that a MeshData is consistent: indices in range, finite points, label and field sizes.
//! \throw core::InputError "name: what" on the first problem.
void validate(const core::MeshData& data, const std::string& name);

//! Read a file and return its triangles (quads split into two triangles, 0-1-2 and 0-2-3) as a
//! surface. Points are all the file's points, unreferenced ones included; labels are kept.
//! \throw core::InputError when the file holds no surface elements.
core::TriMesh read_surface(const std::filesystem::path& path);

//! Write text to a file atomically (used for reports and labelings too).
void write_text_atomic(const std::filesystem::path& path, const std::string& text);

//! Write a labeling (ARCHITECTURE §4): one label in 0..5 per line, in the order of the boundary
//! triangles written as the tet mesh's Triangles block; atomically.
void write_labeling(const std::filesystem::path& path, const std::vector<int>& labels);

}  // namespace polycube::io
