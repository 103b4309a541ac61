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
  bool wrapped = false;  //!< the surface is the input's alpha wrap (`--repair wrap`, or the wrap fallback)
  //! Set when construct_with_wrap_fallback() replaced the surface and `target` by the alpha
  //! wrap: the surface as read (repaired), for the final distance to what the user gave.
  std::optional<core::TriMesh> unwrapped;
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

//! What construct_with_wrap_fallback() did.
struct WrapFallback {
  std::string taken;  //!< "" (the surface as read certified), or "alpha wrap (...)"
  std::string why;    //!< why the surface as read did not construct
};

//! construct_from_input(), and when no attempt can be certified on a surface that is not
//! wrapped yet, the same construction on the surface's alpha wrap (repair/repair.h, with the
//! ball and offset of `wrap_settings`: run's --wrap-alpha and --wrap-offset). Where every attempt
//! leaves a few tets folded, the cause is often a detail thinner than the tets (a slit, a narrow
//! gap) that no chart layout opens, and the wrap closes it. `input` then holds the wrap as its
//! surface and target (the chain's mesh fits the wrap; `unwrapped` keeps the surface as read),
//! and `fallback` says what was done and why. The wrap's construction gets the same budget
//! (options.time_limit) again. `inject_unwrapped_failure` (tests only): the first construction
//! counts as not certified without running.
//! \throw as construct_from_input: the wrap's failure, naming the first one
construct::ConstructResult construct_with_wrap_fallback(ConstructInput& input, const std::filesystem::path& path,
                                                        const construct::ConstructOptions& options,
                                                        const repair::RepairOptions& wrap_settings,
                                                        bool wrap_fallback, bool inject_unwrapped_failure,
                                                        WrapFallback& fallback);

}  // namespace polycube::pipeline
