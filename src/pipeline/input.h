#pragma once
//! \file input.h
//! \brief Reading the input of the construction: a closed triangle surface (.obj .off .stl .ply,
//! or the triangles of a .mesh/.vtk/.msh) or a tet mesh (.mesh .vtk .msh).

#include "construct/construct.h"
#include "core/types.h"
#include "quality/surface_distance.h"
#include "repair/repair.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace polycube::pipeline {

//! The input of a construction.
struct ConstructInput {
  std::optional<core::TetMesh> tets;     //!< set for tet-mesh inputs
  std::optional<core::TriMesh> surface;  //!< set for surface inputs
  //! The surface the results are compared with: the input surface, or the tet mesh's boundary.
  core::TriMesh target;
  //! What the default repairs changed in a surface input (repair/repair.h), a line per kind.
  std::vector<std::string> repairs;
  bool wrapped = false;  //!< the surface is the input's alpha wrap (`--repair wrap`)
  //! The last hex mesh's distance to `target`, kept with its points and hexes: the optimize
  //! stage's checks and the final report measure the meshes the optimizer and the padding have
  //! measured already. A cache: the input itself does not change.
  mutable quality::RememberedDistance distances;
};

//! Read a construction input and check what can be checked before heavy work: a surface gets
//! the repairs that never move it and those `repairs` asks for (each logged as a warning), then
//! must be closed and manifold; a hex mesh is refused.
//! \throw core::InputError naming the file
ConstructInput read_construct_input(const std::filesystem::path& path, const repair::RepairOptions& repairs = {});

//! Run the construction on a read input. InputErrors are re-thrown naming the file.
construct::ConstructResult construct_from_input(const ConstructInput& input,
                                                const std::filesystem::path& path,
                                                const construct::ConstructOptions& options);

}  // namespace polycube::pipeline
