#pragma once
//! \file three_mf.h
//! \brief 3MF assemblies of closed surfaces, for 3D printing the parts of a fabricated shape
//!        (thesis ch. 6), through lib3mf.
//!
//! A 3MF file is a zip package of XML. It stores vertex coordinates as single-precision
//! floats, and lib3mf 1.8 prints them with at most six decimals, truncated, through float
//! arithmetic: a coordinate x comes back within 2^-22 |x| + 1e-6 model units (about two float
//! ulps, plus 1 nm in millimetres), not to the nearest float.

#include "core/types.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace polycube::io {

//! One object of a 3MF assembly: a closed triangle surface in place (model units = mm), with a
//! display colour.
struct ThreeMfObject {
  std::string name;    //!< shown by slicers; may be empty
  core::TriMesh mesh;  //!< #V points (mm, stored as float), #F triangles
  std::array<std::uint8_t, 3> rgb{200, 200, 200};  //!< sRGB display colour, opaque
};

//! Write all objects in one 3MF file: each a mesh object with its own build item (identity
//! transform, so the parts stay where they are and keep their relative placement), unit
//! millimetre, its colour as a base material of one shared group. Written atomically
//! (temporary file in the same folder, then rename); labels of the meshes are not written.
//! \throw core::InputError with one line before any file is created if there is nothing to
//!        write (no objects, an object without triangles), the data is bad (index out of range,
//!        a triangle repeating a vertex, a coordinate non-finite or beyond single precision) or
//!        the path cannot be written (missing folder, a directory, no permission);
//!        core::Error if lib3mf fails while building or writing the package (nothing is left).
void write_3mf(const std::filesystem::path& path, const std::vector<ThreeMfObject>& objects);

//! The mesh objects of a 3MF file in the file's resource order (names and geometry, the
//! colour when the object has a base material, else the default), for tests and round trips.
//! Components objects and build transforms are not applied: each mesh is in its own frame.
//! \throw core::InputError naming the file when it is missing or not a readable 3MF package.
std::vector<ThreeMfObject> read_3mf(const std::filesystem::path& path);

}  // namespace polycube::io
