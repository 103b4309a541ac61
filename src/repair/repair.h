#pragma once
//! \file repair.h
//! \brief Repairs of an input surface: those that never move it (on by default) and those that
//! change its geometry (on request).
//!
//! Meshes as exporters write them are often a triangle soup (OBJ, OFF and PLY writers that give
//! each triangle its own three vertices), or carry triangles that repeat a vertex or repeat
//! another triangle, sheets that touch at a vertex, or triangles turned inward. None of these
//! change the shape, only how it is stored; fixing them is what every other tool of the field
//! does on load. So they are applied by default, in this order, and each is counted:
//!   1. vertices at exactly the same coordinates become one (no tolerance: a tolerance would
//!      move the surface, and may join what the model keeps apart);
//!   2. triangles that use a vertex twice (after 1) are dropped: they have no area;
//!   3. a triangle with the same three vertices in the same turning order as an earlier one is
//!      dropped (the first is kept);
//!   4. vertices no triangle uses are dropped;
//!   5. a vertex where separate sheets touch (its triangles form several fans) becomes one
//!      vertex per fan, at the same place;
//!   6. the triangles are turned consistently and so that the surface bounds its volume
//!      (outer shells facing out, the shells of cavities facing into the cavity).
//! A mesh that needs none of them comes back unchanged, bit for bit (same vertex order).
//!
//! On request, because they change the geometry (RepairOptions): keep only the largest
//! component (by area), fill the holes up to a size with refined, faired patches (CGAL), or
//! replace the surface by its alpha wrap (CGAL 3D alpha wrapping: a watertight, manifold,
//! self-intersection-free surface within an offset of the input, the remedy for soups that do
//! not close, self-intersections and overlapping solids).

#include "core/types.h"

#include <algorithm>
#include <string>
#include <vector>

namespace polycube::repair {

//! The repairs that change the geometry, all off by default.
struct RepairOptions {
  bool largest_component = false;  //!< keep the component of largest area, drop the others
  bool fill_holes = false;         //!< close the holes of at most max_hole_edges edges
  int max_hole_edges = 1000;       //!< larger holes are left open (and reported)
  bool wrap = false;               //!< replace the surface by its alpha wrap
  double wrap_alpha = 0.01;        //!< the wrap's ball radius, a fraction of the bbox diagonal
  double wrap_offset = 0.001;      //!< the wrap's distance to the input, a fraction of the diagonal
};


//! What repair_surface changed.
struct RepairReport {
  int merged_vertices = 0;       //!< vertices joined to an earlier one at the same coordinates
  int degenerate_triangles = 0;  //!< triangles dropped for using a vertex twice
  int duplicate_triangles = 0;   //!< triangles dropped for repeating an earlier one
  int unused_vertices = 0;       //!< vertices dropped for belonging to no triangle
  int split_vertices = 0;        //!< vertices where sheets touched, given one copy per extra fan
  int turned_triangles = 0;      //!< triangles turned to face consistently and outward
  int dropped_components = 0;    //!< components dropped by largest_component
  int dropped_triangles = 0;     //!< their triangles
  int filled_holes = 0;          //!< holes closed by fill_holes
  int hole_triangles = 0;        //!< triangles added to close them
  int open_holes = 0;            //!< holes left open (larger than max_hole_edges)
  bool wrapped = false;          //!< the surface is the input's alpha wrap
  int wrap_triangles = 0;        //!< triangles of the wrap
  double wrap_alpha = 0.0, wrap_offset = 0.0;  //!< in model units

  //! Where the changes are: the first kMaxSites places of each kind, in model coordinates (a
  //! vertex's position, a triangle's or a hole's centre), so a person can find them.
  static constexpr std::size_t kMaxSites = 3;
  struct Sites {
    std::vector<core::Vec3> merged, degenerate, duplicate, split, turned, filled, open;
  } sites;
  //! Add `p` to `list` unless it holds it already or holds kMaxSites places.
  static void note(std::vector<core::Vec3>& list, const core::Vec3& p) {
    if (list.size() < kMaxSites && std::find(list.begin(), list.end(), p) == list.end()) list.push_back(p);
  }

  [[nodiscard]] bool changed() const {
    return merged_vertices + degenerate_triangles + duplicate_triangles + unused_vertices + split_vertices +
               turned_triangles + dropped_components + filled_holes >
           0 || wrapped;
  }
  //! One line per kind of change, e.g. "merged 24 vertices at equal coordinates"; with
  //! `where`, each line ends with the first few places (as `info` prints them).
  [[nodiscard]] std::vector<std::string> lines(bool where = false) const;
};

//! " (first at (x, y, z), (x, y, z))" for the first places of `count` of one kind (" (at ...)"
//! when they are all), or nothing when `places` is empty: how the reports say where.
std::string places_text(const std::vector<core::Vec3>& places, int count);

//! Apply the default repairs above to `mesh`, then those `options` asks for (its labels, if
//! any, follow its triangles; a wrap or a filled hole drops them).
RepairReport repair_surface(core::TriMesh& mesh, const RepairOptions& options = {});

}  // namespace polycube::repair
