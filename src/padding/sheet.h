#pragma once
//! \file sheet.h
//! \brief Sheet insertion over a facet set (thesis §4.2.2, §4.3.3; ARCHITECTURE §6.6).
//!
//! A set PF of facets of a hex mesh (boundary and interior quads) is inflated into one new layer
//! of hexes: pillowing with the whole mesh as shrink set and the unselected boundary facets as
//! "through" facets, so a sheet may end on the boundary. Each selected facet becomes one hex;
//! where two sheets cross along an edge, one more hex fills the crossing.
//!
//! How it works. Around every vertex v the cells touching v are the hexes and, for each boundary
//! facet at v, a "ghost" cell glued outside it. Two cells sharing a facet at v stay together
//! unless the facet is selected; two ghosts meeting at a boundary edge stay together unless an
//! odd number of the edge's facets is selected (a sheet ends there and must reach the outside).
//! Each group of cells (a region) gets its own copy of v; every hex takes the copies of its
//! regions, and the gaps left between regions are filled:
//! - a selected facet -> one hex between its two sides' copies (boundary facet: between the hex
//!   side and the ghost side, which stays on the surface);
//! - an edge whose cells fall into four regions (two sheets crossing, or a sheet crossing a
//!   padded surface) -> one hex whose cross-section is the four regions' copies.
//! Cross-sections with two regions need nothing; a cross-section of three, or of more than four,
//! cannot be filled with hexes and is refused by the rules below.
//!
//! The rules (thesis §4.3.1), checked before anything is built: around an interior edge and a
//! boundary edge of three or more hexes (E3H) an even number of facets is selected; at a boundary
//! edge of two hexes (E2H) the selection is not one surface facet alone (that would notch the
//! surface); at most four separations around any edge. Around an edge of one hex (E1H) anything
//! goes.

#include "core/types.h"

#include <cstdint>
#include <string>
#include <vector>

namespace polycube::padding {

//! Options of insert_sheet().
struct SheetOptions {
  //! A vertex copy moves from the original vertex by this fraction of the mean length of the
  //! vertex's edges, into its region (along the surface when the region touches the outside).
  double offset = 0.3;
};

//! Result of insert_sheet().
struct SheetResult {
  core::HexMesh mesh;  //!< the padded mesh: the input's hexes first (same order), then the new ones
  //! #H': 1 for the new hexes (the padding layer), 0 for the input's
  std::vector<std::uint8_t> padding_layer;
  //! #H': the input hex each hex comes from (itself; for a new hex, the hex on the inner side of
  //! its facet, or the first hex around its crossing edge)
  std::vector<int> source_hex;
  int added_hexes = 0;     //!< hexes of the new layer
  int facet_hexes = 0;     //!< of which one per selected facet
  int crossing_hexes = 0;  //!< of which one per edge where two sheets cross
  int split_vertices = 0;  //!< input vertices that got more than one copy
  double seconds = 0;      //!< wall time
};

//! Where a facet set breaks the rules of the file comment.
struct SelectionCheck {
  int bad_edges = 0;      //!< edges that break a rule
  std::string first;      //!< the first of them, named by its vertices, position and rule; empty when valid
  [[nodiscard]] bool ok() const { return bad_edges == 0; }
};

//! Check a facet selection (#F flags, one per facet of core::unique_faces(mesh), in its order) against the rules.
//! \throw core::InputError when selected has the wrong size
SelectionCheck check_selection(const core::HexMesh& mesh, const std::vector<std::uint8_t>& selected);

//! Inflate a sheet of hexes along the selected facets (#F flags, one per facet of core::unique_faces(mesh), in its order).
//! \throw core::InputError when the selection breaks the rules (one line: the first bad edge and
//!        how many there are), is empty, or the mesh's boundary is not a closed 2-manifold
//! \throw core::GeometryError when the result would not be a valid hex mesh (a configuration the
//!        insertion cannot fill, e.g. three sheets crossing at one vertex); nothing is returned
SheetResult insert_sheet(const core::HexMesh& mesh, const std::vector<std::uint8_t>& selected,
                         const SheetOptions& options = {});

//! Selection flags from facets given by their vertex ids (any rotation or direction of each quad).
//! \throw core::InputError naming the first quad that is not a facet of the mesh
std::vector<std::uint8_t> select_facets(const core::HexMesh& mesh, const std::vector<core::Quad>& quads);

//! Every boundary facet selected: global padding.
std::vector<std::uint8_t> boundary_selection(const core::HexMesh& mesh);

}  // namespace polycube::padding
