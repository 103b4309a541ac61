#pragma once
//! \file centre_frames.h
//! \brief The centre Jacobian of hexes as extra elements of the optimization energy
//! (ARCHITECTURE §6.5).
//!
//! Verdict's hex scaled Jacobian, which the fold-over check and every quality figure use, is the
//! minimum over the 8 corners and the centre, whose frame is the three principal axes
//! X1 = (p1+p2+p5+p6)-(p0+p3+p4+p7), X2, X3. The corner tets alone do not see the centre: a hex
//! twisted about one axis keeps all 8 corners positive while its centre determinant is negative,
//! and an optimizer that only raises corners leaves it so (hexes of padded layers on creased or
//! thin parts). Every hex therefore gets a ninth element, the "centre tet"
//! (F-, F-+X1/4, F-+X2/4, F-+X3/4) with F- the centroid of the face opposite X1: its Jacobian
//! matrix is [X1 X2 X3]/4, so the energy's barrier and shape term act on Verdict's centre value.
//! Its points are derived from the hex's vertices (solve::with_derived_points, in two levels: the
//! six face centroids, then the two tips that combine three of them), so the Newton system keeps
//! the mesh's own variables.

#include "core/types.h"
#include "solve/untangle.h"

#include <array>
#include <vector>

namespace polycube::optimize {

//! Normalized centre determinant det(X1,X2,X3)/(|X1||X2||X3|) of one hex (0 when degenerate).
double centre_value(const core::HexMesh& mesh, const core::Hex& h);

//! Reference lengths of every hex's centre tet: |Xi|/4 of the input (the hex size where an axis
//! has collapsed), times scale[c].
std::vector<std::array<double, 3>> centre_lengths(const core::HexMesh& mesh,
                                                  const std::vector<double>& size,
                                                  const std::vector<double>& scale);

//! The centre tet of every hex appended to `elements`, its derived points to the reduction (all
//! hexes, not only those whose centre is their worst point: a barrier on the others keeps a
//! round from twisting them).
//! \param lengths    #H reference lengths (centre_lengths)
//! \param multiplier #H weight factors
//! \param weight     weight of a centre tet relative to a corner tet of the same reference
//! \return the reduction extended by 8 derived points per hex
solve::LinearReduction with_centre_tets(const solve::LinearReduction& reduction,
                                        const core::HexMesh& mesh,
                                        const std::vector<std::array<double, 3>>& lengths,
                                        const std::vector<double>& multiplier, double weight,
                                        solve::TetElements& elements);

}  // namespace polycube::optimize
