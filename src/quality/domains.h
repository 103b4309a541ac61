#pragma once
//! \file domains.h
//! \brief Base-complex blocks of a hex mesh (#D, thesis Table 3.1) and patches of a quad layout
//! (#dom, thesis Table 3.2), counted as cinolib counts them (compute_coarse_hex_layout /
//! compute_coarse_quad_layout), ARCHITECTURE §6.1.
//!
//! Hex mesh: every face incident to a singular edge (singularities.h) starts a sheet. A sheet
//! grows from a face f across each of its non-singular edges e to the faces of e that share no
//! hex with f: at a regular interior edge (4 hexes) this is the one face straight across, at a
//! regular boundary edge it continues only along the boundary surface; singular edges stop it.
//! The blocks are the connected components of hexes across the faces no sheet reached. Faces of
//! the boundary may be traced (sheets seeded at boundary singular edges run over the boundary
//! surface), which changes nothing since no hex lies beyond them.
//!
//! Quad mesh: every edge incident to a singular vertex starts a separatrix, which continues at
//! each non-singular vertex v to the edges of v that share no quad with the current edge (straight
//! on at a regular interior vertex, along the boundary at a regular boundary vertex) and stops at
//! singular vertices. The patches are the connected components of quads across untraced edges.
//!
//! A mesh without singularities (a gridded torus, a periodic grid) has one domain per connected
//! component. Components and blocks are numbered by their lowest element.

#include "core/types.h"
#include "quality/singularities.h"
#include "quality/structure_topology.h"

#include <cstdint>
#include <string>
#include <vector>

namespace polycube::quality {

//! Options of the domain counts.
struct DomainOptions {
  bool keep_labels = true;  //!< fill the per-element block/patch ids and the traced flags
};

//! Base complex of a hex mesh.
struct HexDomains {
  int domains = 0;            //!< #D: number of blocks
  int separating_faces = 0;   //!< interior faces on traced sheets (the blocks' interfaces)
  std::vector<int> block_id;  //!< #C: block of each hex (empty unless keep_labels)
  std::vector<std::uint8_t> face_traced;  //!< #F (HexTopology face order): 1 on a sheet (idem)

  //! Block ids as a cell field (for VTK output). \pre labels were kept.
  [[nodiscard]] core::Field field(const std::string& name = "block_id") const;
};

//! Base-complex blocks of a hex mesh. \throw as hex_topology
HexDomains hex_domains(const core::HexMesh& mesh, const DomainOptions& options = {});
//! Same, reusing the topology and singularities already computed for this mesh.
HexDomains hex_domains(const core::HexMesh& mesh, const HexTopology& topology,
                       const HexSingularities& singularities, const DomainOptions& options = {});

//! Patches of the quad layout of a quad mesh.
struct QuadDomains {
  int domains = 0;                        //!< #dom: number of patches
  int separating_edges = 0;               //!< edges with two or more quads on traced separatrices
  std::vector<int> patch_id;              //!< #C: patch of each quad (empty unless keep_labels)
  std::vector<std::uint8_t> edge_traced;  //!< #E (QuadTopology edge order): 1 on a separatrix

  //! Patch ids as a cell field (for VTK output). \pre labels were kept.
  [[nodiscard]] core::Field field(const std::string& name = "patch_id") const;
};

//! Patches of the quad layout of a quad mesh. \throw core::InputError on out-of-range indices
QuadDomains quad_domains(const core::QuadMesh& mesh, const DomainOptions& options = {});
//! Same, reusing the topology and singularities already computed for this mesh.
QuadDomains quad_domains(const core::QuadMesh& mesh, const QuadTopology& topology,
                         const QuadSingularities& singularities, const DomainOptions& options = {});

}  // namespace polycube::quality
