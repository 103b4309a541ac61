//! Exact booleans of the samples' CSG toolkit (CGAL corefinement). Kept in its own file: the
//! corefinement headers are the slowest part of the module to compile.
#include "samples/cgal_mesh.h"

#include "core/errors.h"

#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <array>
#include <utility>

namespace polycube::samples::detail {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;

//! Carries each triangle's facet id through the corefinement: split faces pass their id to
//! their pieces, copied faces keep theirs.
class FacetVisitor : public PMP::Corefinement::Default_visitor<SurfaceMesh> {
 public:
  FacetVisitor(SurfaceMesh& a, SurfaceMesh& b, SurfaceMesh& out)
      : maps_{{{&a, facet_map(a)}, {&b, facet_map(b)}, {&out, facet_map(out)}}} {}

  void before_subface_creations(FaceIndex f_old, SurfaceMesh& tm) { current_ = map(tm)[f_old]; }
  void after_subface_created(FaceIndex f_new, SurfaceMesh& tm) { map(tm)[f_new] = current_; }
  void after_face_copy(FaceIndex f_src, const SurfaceMesh& tm_src, FaceIndex f_tgt,
                       SurfaceMesh& tm_tgt) {
    map(tm_tgt)[f_tgt] = map(tm_src)[f_src];
  }

 private:
  FacetMap map(const SurfaceMesh& tm) const {
    for (const auto& [mesh, facets] : maps_)
      if (mesh == &tm) return facets;
    PC_REQUIRE(false, "corefinement visitor: unknown mesh");
    return {};
  }

  std::array<std::pair<const SurfaceMesh*, FacetMap>, 3> maps_;
  int current_ = -1;
};

enum class Op { Union, Difference };

Solid boolean(const Solid& a, const Solid& b, Op op) {
  // Corefinement modifies both operands: work on copies so the inputs stay shareable.
  SurfaceMesh ma = a.impl().mesh;
  SurfaceMesh mb = b.impl().mesh;
  SurfaceMesh out;
  FacetVisitor visitor(ma, mb, out);
  // EPICK: predicates are exact and intersection points are constructed exactly before being
  // rounded to double, which is robust for the axis-aligned shapes built here.
  const auto np = CGAL::parameters::visitor(visitor);
  const bool ok = op == Op::Union ? PMP::corefine_and_compute_union(ma, mb, out, np)
                                  : PMP::corefine_and_compute_difference(ma, mb, out, np);
  if (!ok)
    throw core::InternalError(std::string("sample CSG: the ") +
                              (op == Op::Union ? "union" : "difference") +
                              " is not a manifold surface");
  out.collect_garbage();
  // The corefinement's triangulation depends on the process's heap layout: make it canonical.
  return make_solid(canonicalize(out));
}

}  // namespace

Solid unite(const Solid& a, const Solid& b) { return boolean(a, b, Op::Union); }
Solid subtract(const Solid& a, const Solid& b) { return boolean(a, b, Op::Difference); }

}  // namespace polycube::samples::detail
