#pragma once
//! \file vertex_roles.h
//! \brief Which target entity each hex-mesh vertex follows during optimization: nothing
//! (interior), the surface, a feature line, or a corner (fixed).

#include "core/types.h"
#include "optimize/features.h"

#include <vector>

namespace polycube::optimize {

enum class VertexRole { Interior, Surface, Feature, Corner };

//! Roles of the vertices of a hex mesh.
struct VertexRoles {
  std::vector<VertexRole> role;     //!< #V
  std::vector<int> corner;          //!< #V: index into target.features().corners, or -1
  std::vector<double> edge_length;  //!< #V mean edge length of the vertex's hexes (0 if none)
  int surface = 0, feature = 0, corners = 0;  //!< counts (surface excludes feature and corner)
};

//! Classify the vertices of a hex mesh. Boundary edges (between two boundary quads) whose
//! dihedral angle exceeds `angle_degrees` and whose ends lie within `distance` local edge
//! lengths of a target feature line are sharp; their vertices are Feature vertices, those where
//! three or more sharp edges meet are Corner vertices when a target corner lies within the same
//! distance (each target corner taken by its nearest such vertex only). Other boundary
//! vertices are Surface vertices. Without target features, every boundary vertex is Surface.
//! \throw core::InputError on out-of-range indices
VertexRoles classify_vertices(const core::HexMesh& mesh, const TargetSurface& target, double angle_degrees,
                              double distance);

}  // namespace polycube::optimize
