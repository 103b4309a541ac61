#pragma once
//! \file distortion.h
//! \brief Distortion of a tet map: one tet connectivity with two vertex position arrays (source
//! = model space, target = polycube space), ARCHITECTURE §6.1.
//!
//! Per tet, the map is affine, with Jacobian J = T S^-1 (S, T the 3x3 edge matrices
//! [p1-p0, p2-p0, p3-p0] in source and target space) and singular values s1 >= s2 >= s3 > 0:
//! - isometric distortion max(s1, 1/s3)          (1 for a rigid motion)
//! - conformal distortion s1 / s3                (1 for a similarity)
//! - volume distortion    max(det J, 1/det J), det J = s1 s2 s3 (1 for a volume-preserving map);
//!   the signed ratio det J is kept per tet as well.
//! A tet is inverted or flat in a space when its orientation there is not positive, decided by
//! CGAL's exact orientation predicate; such tets have no finite distortion: they are counted,
//! given +infinity per tet, and left out of the averages and maxima.
//! Averages are weighted by the tets' source volumes.

#include "core/types.h"

#include <string>
#include <vector>

namespace polycube::quality {

//! Options of map_distortion.
struct DistortionOptions {
  //! Scale the target positions uniformly (about the origin) so that the total target volume
  //! equals the total source volume before measuring: the isometric distortion then ignores a
  //! global change of size. Default off.
  bool normalize_volume = false;
  bool keep_per_tet = true;  //!< fill the per-tet vectors
};

//! Average and maximum of one distortion measure over the valid tets.
struct DistortionStat {
  double average = 0.0;  //!< source-volume-weighted mean over valid tets (0 when there is none)
  double max = 0.0;      //!< maximum over valid tets (0 when there is none)
};

//! Distortion of a tet map.
struct MapDistortion {
  int tets = 0;               //!< #T
  int inverted_source = 0;    //!< tets inverted or flat in the source (exact predicate)
  int inverted_target = 0;    //!< tets inverted or flat in the target (exact predicate)
  int invalid = 0;            //!< tets inverted or flat in either space
  double target_scale = 1.0;  //!< factor applied to the target (1 unless normalize_volume)
  DistortionStat isometric;   //!< max(s1, 1/s3)
  DistortionStat conformal;   //!< s1 / s3
  DistortionStat volume;      //!< max(det J, 1/det J)
  std::vector<double> per_tet_isometric;     //!< #T (+inf for invalid tets), when kept
  std::vector<double> per_tet_conformal;     //!< #T (+inf for invalid tets), when kept
  std::vector<double> per_tet_volume;        //!< #T max(det J, 1/det J) (+inf for invalid tets)
  std::vector<double> per_tet_volume_ratio;  //!< #T signed det J (0 when the source tet is flat)

  //! The per-tet measures as cell fields ("isometric", "conformal", "volume"), infinities
  //! replaced by -1 so that every VTK reader accepts them. \pre per-tet values were kept.
  [[nodiscard]] std::vector<core::Field> fields() const;
};

//! Distortion of the map from source.points to target_points over source's tets.
//! \param source tet connectivity and source positions
//! \param target_points #V target positions (same indexing)
//! \throw core::InputError when the sizes differ, an index is out of range or a coordinate is
//!        not finite
MapDistortion map_distortion(const core::TetMesh& source,
                             const std::vector<core::Vec3>& target_points,
                             const DistortionOptions& options = {});

}  // namespace polycube::quality
