#pragma once
//! \file scaled_jacobian.h
//! \brief Scaled Jacobian of hexahedra, tetrahedra and quads, exactly as Verdict defines it
//! (ARCHITECTURE §6.1), with degenerate elements reported as invalid instead of "perfect".
//!
//! Verdict (Sandia's mesh-quality library, used by VTK's vtkMeshQuality and ParaView):
//! - hex: the minimum over 9 normalized determinants det(a,b,c)/(|a||b||c|): one at each corner
//!   from its three outgoing edges (neighbours core::kHexCornerNeighbors) and one at the centre
//!   from the principal axes X1 = (p1+p2+p5+p6)-(p0+p3+p4+p7), X2 = (p2+p3+p6+p7)-(p0+p1+p4+p5),
//!   X3 = (p4+p5+p6+p7)-(p0+p1+p2+p3). Verdict returns 1e30 when one of these 27 vectors has
//!   squared length <= 1e-30 (VERDICT_DBL_MIN).
//! - tet: sqrt(2) det(p1-p0, p2-p0, p3-p0) / L, L the largest of the four corner products of
//!   the three edge lengths at a corner (and at least |det|); 1e30 when L < 1e-30.
//! - quad: the minimum over the 4 corners of n . (e_prev x e_next) / (|e_prev||e_next|), n the
//!   unit normal at the centre ((e0 - e2) x (e1 - e3) normalized, e_i = p_{i+1} - p_i); 0 when
//!   an edge is shorter than 1e-30.
//!
//! Every value lies in [-1, 1] (Hadamard's inequality); rounding beyond is clamped.
//!
//! **Degenerate elements are invalid.** An element is degenerate when one of the vectors
//! entering its measure has zero length: squared length <= 1e-30 as in Verdict, or length
//! <= 1e-12 times the element's longest edge (a collapsed edge of a mesh of any scale), or when
//! a coordinate is not finite. Verdict calls such an element perfect (1e30); here it gets the
//! value kInvalidScaledJacobian (-1) and valid == false, and mesh summaries count it apart.

#include "core/types.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace polycube::quality {

//! Value given to degenerate (invalid) elements: the worst possible scaled Jacobian.
inline constexpr double kInvalidScaledJacobian = -1.0;

//! Verdict's VERDICT_DBL_MIN: vectors with a squared length at or below it are degenerate.
inline constexpr double kVerdictDblMin = 1.0e-30;

//! Relative length (w.r.t. the element's longest edge) at or below which a vector is degenerate.
inline constexpr double kRelativeDegenerateLength = 1.0e-12;

//! Scaled Jacobian of one element.
struct ElementJacobian {
  double value = kInvalidScaledJacobian;  //!< in [-1, 1]; kInvalidScaledJacobian when !valid
  bool valid = false;                     //!< false for a degenerate element (see file comment)
};

//! Verdict's hex scaled Jacobian. \param p the 8 corners in the order of core/elements.h.
ElementJacobian hex_scaled_jacobian(const std::array<core::Vec3, 8>& p);

//! Verdict's tet scaled Jacobian. \param p the 4 corners (positive: (p1-p0).((p2-p0)x(p3-p0)) > 0).
ElementJacobian tet_scaled_jacobian(const std::array<core::Vec3, 4>& p);

//! Verdict's quad scaled Jacobian (corner normalized cross products projected on a normal).
//! \param p the 4 corners, counter-clockwise seen from the side the normal points to
//! \param reference_normal when given (non-zero, any length), used instead of Verdict's own
//!        centre normal: then a quad whose corners turn clockwise around it gets negative values
//!        (an inverted quad of a planar or oriented surface). Without it the value is Verdict's,
//!        which cannot see a quad flipped as a whole.
ElementJacobian quad_scaled_jacobian(
    const std::array<core::Vec3, 4>& p,
    const std::optional<core::Vec3>& reference_normal = std::nullopt);

//! Histogram bins of a summary: bin 0 is [-1, 0] (inverted and invalid elements), bin k >= 1 is
//! (0.2 (k-1), 0.2 k]; values are clamped to [-1, 1] so every element falls in one bin.
inline constexpr int kHistogramBins = 6;

//! Lower edge of histogram bin i (bin 0 starts at -1; bin i >= 1 starts at 0.2 (i-1)).
constexpr double histogram_bin_lower(int i) { return i == 0 ? -1.0 : (i - 1) / 5.0; }
//! Upper edge of histogram bin i.
constexpr double histogram_bin_upper(int i) { return i == 0 ? 0.0 : i / 5.0; }

//! Scaled Jacobian of every element of a mesh, and its summary.
struct ScaledJacobianSummary {
  int count = 0;  //!< number of elements
  double min =
      0.0;  //!< minimum over all elements (kInvalidScaledJacobian if one is invalid); 0 when empty
  double max = 0.0;  //!< maximum over all elements; 0 when empty
  //! Average over all elements (invalid ones count with kInvalidScaledJacobian); 0 when empty.
  double average = 0.0;
  int inverted = 0;  //!< valid elements with value <= 0
  int invalid = 0;   //!< degenerate elements (not counted in inverted)
  std::array<int, kHistogramBins>
      histogram{};             //!< element counts per bin (see histogram_bin_lower)
  std::vector<double> values;  //!< #C per-element values (empty when not kept)

  //! No inverted and no invalid element.
  [[nodiscard]] bool all_positive() const { return inverted == 0 && invalid == 0; }
  //! The per-element values as a cell field (for VTK output). \pre values were kept.
  [[nodiscard]] core::Field field(const std::string& name = "scaled_jacobian") const;
};

//! Options of the mesh-level functions.
struct ScaledJacobianOptions {
  bool keep_values = true;  //!< fill ScaledJacobianSummary::values
};

//! Scaled Jacobian of every hex. \throw core::InputError on out-of-range vertex indices.
ScaledJacobianSummary scaled_jacobian(const core::HexMesh& mesh,
                                      const ScaledJacobianOptions& options = {});
//! Scaled Jacobian of every tet. \throw core::InputError on out-of-range vertex indices.
ScaledJacobianSummary scaled_jacobian(const core::TetMesh& mesh,
                                      const ScaledJacobianOptions& options = {});
//! Scaled Jacobian of every quad.
//! \param reference_normals empty (Verdict's own centre normals) or #C normals, one per quad
//! \throw core::InputError on out-of-range vertex indices or a wrong number of normals
ScaledJacobianSummary scaled_jacobian(const core::QuadMesh& mesh,
                                      const ScaledJacobianOptions& options = {},
                                      const std::vector<core::Vec3>& reference_normals = {});

}  // namespace polycube::quality
