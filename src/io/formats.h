#pragma once
//! \file formats.h
//! \brief Internal per-format readers and writers of io/ (the public API is mesh_io.h).
//!
//! Readers take the whole file in memory and the name to use in messages; they return the
//! data or throw core::InputError. Writers return the file content; mesh_io.cpp checks first
//! that the data fits the format (see capabilities()) and writes the file atomically.

#include "core/types.h"
#include "io/mesh_io.h"

#include <string>
#include <string_view>
#include <vector>

namespace polycube::io::detail {

//! What a format can store. Anything else is refused (elements) or dropped with a warning
//! (attributes) by write_mesh.
struct Capabilities {
  bool triangles = false;
  bool quads = false;        //!< STL: quads are split into two triangles instead
  bool tets = false;
  bool hexes = false;
  bool edges = false;
  bool cell_labels = false;  //!< labels of triangles/quads/tets/hexes (and edges if edges)
  bool point_labels = false;
  bool point_data = false;
  bool cell_data = false;
};

Capabilities capabilities(Format f);

core::MeshData read_obj(std::string_view data, const std::string& name);
core::MeshData read_off(std::string_view data, const std::string& name);
core::MeshData read_stl(std::string_view data, const std::string& name);
core::MeshData read_ply(std::string_view data, const std::string& name);
core::MeshData read_medit(std::string_view data, const std::string& name);
core::MeshData read_vtk(std::string_view data, const std::string& name);
core::MeshData read_msh(std::string_view data, const std::string& name);

//! Writers: the data has been validated and reduced to what the format holds.
std::string write_obj(const core::MeshData& d, const WriteOptions& o);
std::string write_off(const core::MeshData& d, const WriteOptions& o);
std::string write_stl(const core::MeshData& d, const WriteOptions& o);
std::string write_ply(const core::MeshData& d, const WriteOptions& o);
std::string write_medit(const core::MeshData& d, const WriteOptions& o);
std::string write_vtk(const core::MeshData& d, const WriteOptions& o);
std::string write_msh(const core::MeshData& d, const WriteOptions& o);

//! Append a polygon of 3 or more 0-based vertex indices: a triangle or a quad is kept as it
//! is, a larger polygon is fan-triangulated from its first vertex (n - 2 triangles).
void add_polygon(core::MeshData& d, const std::vector<int>& poly);

//! Name of the cell-data / point-data field that carries labels in formats without a native
//! place for them (VTK): written when labels exist, turned back into labels on reading.
inline constexpr const char* kLabelField = "label";

}  // namespace polycube::io::detail
