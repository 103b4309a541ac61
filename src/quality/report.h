#pragma once
//! \file report.h
//! \brief One-call quality reports of hex, tet and quad meshes: the numbers of the thesis's
//! tables (Table 3.1: #H, mSJ/aSJ, #D; Table 3.2: #sv, #dom; Table 4.1: #H, #Sv, #Se, mSJ,
//! aSJ), computed with one shared topology.

#include "core/types.h"
#include "quality/domains.h"
#include "quality/scaled_jacobian.h"
#include "quality/singularities.h"
#include "quality/surface_distance.h"

#include <optional>
#include <vector>

namespace polycube::quality {

//! What a report computes.
struct ReportOptions {
  bool structure = true;         //!< singularities and domains (hex and quad meshes)
  bool surface_layout = true;    //!< hex meshes: #sv and #dom of the boundary quad mesh
  bool keep_per_element = true;  //!< keep per-element values (SJ, block ids) for output
  //! When set, the symmetric Hausdorff distance between the mesh's boundary (hex meshes) or
  //! surface (quad meshes) and this reference surface.
  const core::TriMesh* target = nullptr;
  SurfaceDistanceOptions distance;  //!< options of that distance
};

//! Report of a hex mesh.
struct HexReport {
  int hexes = 0;             //!< #H
  int vertices = 0;          //!< referenced or not
  ScaledJacobianSummary sj;  //!< mSJ = sj.min, aSJ = sj.average, inverted, invalid, histogram
  std::optional<HexSingularities> singularities;  //!< #Sv, #Se (when options.structure)
  std::optional<HexDomains> domains;              //!< #D (when options.structure)
  int surface_singular_vertices = -1;  //!< #sv of the boundary quad mesh (-1 when not computed)
  int surface_domains = -1;            //!< #dom of the boundary quad mesh (-1 when not computed)
  std::optional<SurfaceDistance> distance;  //!< boundary vs options.target (when given)

  //! Per-hex cell fields for output: "scaled_jacobian" and, when computed, "block_id".
  [[nodiscard]] std::vector<core::Field> fields() const;
};

//! Report of a tet mesh.
struct TetReport {
  int tets = 0;  //!< #T
  int vertices = 0;
  ScaledJacobianSummary sj;  //!< Verdict tet scaled Jacobian
  [[nodiscard]] std::vector<core::Field> fields() const;
};

//! Report of a quad mesh.
struct QuadReport {
  int quads = 0;  //!< #Q
  int vertices = 0;
  ScaledJacobianSummary sj;  //!< Verdict quad scaled Jacobian (centre normals)
  std::optional<QuadSingularities> singularities;  //!< #sv (when options.structure)
  std::optional<QuadDomains> domains;              //!< #dom (when options.structure)
  std::optional<SurfaceDistance> distance;         //!< surface vs options.target (when given)
  //! Per-quad cell fields: "scaled_jacobian" and, when computed, "patch_id".
  [[nodiscard]] std::vector<core::Field> fields() const;
};

//! Analyse a hex mesh. \throw core::InputError on bad indices, core::GeometryError on a face
//! shared by more than two hexes (structure), and as hausdorff_distance
HexReport hex_report(const core::HexMesh& mesh, const ReportOptions& options = {});
//! Analyse a tet mesh. \throw core::InputError on bad indices
TetReport tet_report(const core::TetMesh& mesh, const ReportOptions& options = {});
//! Analyse a quad mesh. \throw core::InputError on bad indices, and as hausdorff_distance
QuadReport quad_report(const core::QuadMesh& mesh, const ReportOptions& options = {});

}  // namespace polycube::quality
