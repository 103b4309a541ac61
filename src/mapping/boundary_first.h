#pragma once
//! \file boundary_first.h
//! \brief Boundary-first placement of a polycube map (ARCHITECTURE §6.2 step 4, a repair): when
//! the free-boundary untangling stays stuck, build a valid polycube surface first, then the
//! volume inside it.
//!
//! The free-boundary untangling fails at concave corners and where the chain of vertices along a
//! polycube edge runs backwards (a turning point): the boundary itself is folded there and the
//! tets cannot unfold it. With the corners where the deformation put them, this repair
//! 0. moves chart planes apart where a polycube edge runs the other way than its chain does in
//!    the model (the faces along it would wind the wrong way round);
//! 1. places every polycube-edge chain on the straight segment between its two corners, at the
//!    model's arc-length fractions (monotone by construction);
//! 2. maps each chart inside its now fixed rectilinear polygon by a fixed-boundary 2D elliptic
//!    untangling (each chart triangle is lifted to a tet whose apex follows its first vertex at a
//!    fixed height, so the tet's Jacobian is the triangle's 2D Jacobian plus the unit normal);
//! 3. untangles the interior with the whole boundary fixed (the fixed-boundary problem of
//!    Garanzha et al. 2021, which is far better behaved than the free-boundary one).
//! The caller then lowers the distortion with the boundary free again, starting from this valid
//! state (the barrier keeps it valid).

#include "core/types.h"
#include "solve/untangle.h"

#include <string>
#include <vector>

namespace polycube::mapping {

//! Result of place_boundary_first().
struct BoundaryFirstResult {
  bool valid = false;                //!< every tet positive and every boundary triangle faces its label
  int chains = 0;                    //!< polycube-edge chains placed
  int reversed_chains = 0;           //!< of those, running the other way than in the model (step 0)
  int charts_inverted = 0;           //!< chart triangles facing away after the 2D step
  int tets_inverted = 0;             //!< tets with det <= 0 after the volume step
  int locked_inverted = 0;           //!< of those, tets or triangles whose every vertex was fixed
  //! Chart triangles whose three vertices all sit on polycube edges (so the chain placement
  //! alone decides their orientation) and that face away: the placement stops before the 2D
  //! step. Splitting their edges that cross the chart frees a vertex in its plane.
  std::vector<int> locked_triangles;
  solve::UntangleResult chart_step;  //!< the 2D untangling's report
  solve::UntangleResult volume_step; //!< the volume untangling's report
  std::string reason;                //!< why it failed (empty when valid)
  //! When the charts were placed but tets stay inverted: the placement (every boundary
  //! triangle facing its label, the interior as the volume step left it); empty otherwise.
  std::vector<core::Vec3> placement;
};

//! Place the polycube boundary first, then the volume (see the file comment).
//! \param points        #V model positions (the reference shapes)
//! \param tets          #T tets, positive in points
//! \param tris          #B outward boundary triangles
//! \param labels        #B labels in 0..5
//! \param vertex_group  3#V chart coordinate group of (vertex, axis), -1 when free
//! \param P             #V polycube positions (chart coordinates exact); replaced only when the
//!                      result is valid
//! \param base          untangling options (iterations, λ, min det target)
//! \param h             apex height of the lifted chart triangles (model length)
//! \param fast_sigma    above base.min_sigma: the volume step runs first with ε falling at least
//!                      this fraction per outer iteration, and again with base's schedule where
//!                      that leaves tets inverted (solve::untangle_fast_first;
//!                      volume_step.slower_schedule); otherwise base's schedule alone
BoundaryFirstResult place_boundary_first(const std::vector<core::Vec3>& points, const std::vector<core::Tet>& tets,
                                         const std::vector<core::Tri>& tris, const std::vector<int>& labels,
                                         const std::vector<int>& vertex_group, std::vector<core::Vec3>& P,
                                         const solve::UntangleOptions& base, double h, double fast_sigma);

//! The placement's tangle between its fixed boundary is usually a few tets, and from ε = 1 the
//! paper's schedule (a tenth per iteration) mostly waits for ε to come down to their |det|: a
//! fifth reaches them in about half the iterations on the shared shapes (bench/RESULTS.md, stop 57).
inline constexpr double kFastPlacementSigma = 0.2;

}  // namespace polycube::mapping
