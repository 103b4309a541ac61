#pragma once
//! \file tet_locator.h
//! \brief Point location in a tet mesh with a uniform grid of tet bounding boxes.
//!
//! Deterministic: a point is assigned to the tet with the largest *signed distance score*
//! (the smallest signed distance from the point to the planes of the tet's four faces: positive
//! inside, the distance to the nearest face; negative outside). A point strictly inside one tet
//! (score above a tiny threshold) gets that tet; a point on shared faces, edges or vertices gets
//! the candidate with the largest score, ties going to the smallest tet id, so the answer never
//! depends on evaluation order.

#include "core/types.h"

#include <array>
#include <vector>

namespace polycube::mesh {

//! Uniform-grid point locator over the tets of a mesh. Flat tets (|det| at most 1e-14 times
//! the cube of their longest edge) are not indexed.
class TetLocator {
 public:
  //! Result of a query.
  struct Hit {
    int tet = -1;                  //!< located tet, -1 when none
    std::array<double, 4> bary{};  //!< barycentric coordinates in that tet (sum 1)
    double score = -1e300;         //!< signed distance score (>= 0 inside)
  };

  //! \param tets   #T tets (indices into points)
  //! \param points #V positions
  //! \param tolerance points up to this distance outside a tet may be located in it (absolute)
  TetLocator(const std::vector<core::Tet>& tets, const std::vector<core::Vec3>& points,
             double tolerance);

  //! The tet containing q (score >= -tolerance), or tet = -1.
  [[nodiscard]] Hit locate(const core::Vec3& q) const;

  //! The tet of largest score among those registered within `rings` grid cells of q's cell
  //! (q clamped to the grid); tet = -1 only when that neighbourhood is empty.
  [[nodiscard]] Hit nearest(const core::Vec3& q, int rings) const;

  //! The tet of largest score over all tets (brute force; for the rare points nothing else finds).
  [[nodiscard]] Hit nearest_brute_force(const core::Vec3& q) const;

  [[nodiscard]] double tolerance() const { return tolerance_; }
  [[nodiscard]] int num_indexed() const { return static_cast<int>(tet_ids_.size()); }

 private:
  struct TetData {
    core::Vec3 p0;
    Eigen::Matrix3d inv;  // rows: gradients of barycentric coordinates 1, 2, 3
    std::array<double, 4>
        height;  // 1 / |gradient of barycentric i|: distance of vertex i to its face
  };
  void evaluate(int slot, const core::Vec3& q, Hit& best) const;
  [[nodiscard]] std::array<int, 3> cell_of(const core::Vec3& q) const;

  std::vector<int> tet_ids_;   // indexed tets (original ids), increasing
  std::vector<TetData> data_;  // per indexed tet
  core::Vec3 origin_;
  core::Vec3 inv_cell_;  // 1 / cell size per axis
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<int> cell_start_;  // CSR: slots of each grid cell
  std::vector<int> cell_items_;
  double tolerance_ = 0.0;
  double inside_threshold_ = 0.0;  // a score above this means strictly inside: stop searching
};

//! The tet containing q, else the tet of largest score nearby, else over all tets; sets `located`
//! to whether q was inside (within the tolerance).
TetLocator::Hit locate_or_nearest(const TetLocator& locator, const core::Vec3& q, bool& located);

//! The point of `to` with the barycentric coordinates of a hit in tet `tet` (negative
//! coordinates, from points just outside, clamped to 0 and the rest renormalized).
core::Vec3 map_through(const std::vector<core::Tet>& tets, const std::vector<core::Vec3>& to,
                       const TetLocator::Hit& hit);

}  // namespace polycube::mesh
