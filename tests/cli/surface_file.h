#pragma once
// Write a triangle surface to a file for the CLI tests (format from the extension).
#include "core/types.h"
#include "io/mesh_io.h"

#include <filesystem>

namespace polycube::test {

inline void write_surface(const std::filesystem::path& p, const core::TriMesh& m) {
  core::MeshData d;
  d.points = m.points;
  d.triangles = m.cells;
  io::write_mesh(p, d);
}

}  // namespace polycube::test
