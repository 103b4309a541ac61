#pragma once
//! \file polycube_map_io.h
//! \brief Reading and writing polycube maps as two MEDIT `.mesh` files with identical
//! `Tetrahedra` blocks (ARCHITECTURE §4, the convention of the field).

#include "core/polycube_map.h"

#include <filesystem>

namespace polycube::io {

//! Read a map from its model-space and polycube-space tet meshes (any volume format io reads;
//! MEDIT `.mesh` is the convention). Other blocks (Triangles, ...) are ignored.
//! \throw core::InputError naming the file when a file is unreadable or holds no tetrahedra,
//!        when the vertex counts differ, or "connectivity differs: tet 17 is (...) in a but (...)
//!        in b" when the Tetrahedra blocks differ
core::PolycubeMap read_polycube_map(const std::filesystem::path& model_path,
                                    const std::filesystem::path& polycube_path);

//! Write a map as two files (atomic each): the tets, and the boundary triangles of the tet mesh
//! (faces of exactly one tet, outward for positive tets) as the `Triangles` block with their
//! polycube label (0..5 = +X, -X, +Y, -Y, +Z, -Z: dominant axis of the polycube-space normal) as
//! reference; the same triangles in the same order in both files.
//! The map is not validated (an invalid map can be written for inspection).
//! \throw core::InputError on inconsistent sizes or indices, core::Error on I/O failure
void write_polycube_map(const std::filesystem::path& model_path,
                        const std::filesystem::path& polycube_path, const core::PolycubeMap& map);

}  // namespace polycube::io
