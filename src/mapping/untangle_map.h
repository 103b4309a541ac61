#pragma once
//! \file untangle_map.h
//! \brief Untangling of a polycube map under its chart constraints (ARCHITECTURE §6.2 step 5):
//! the global elliptic optimization and the local repair of what it leaves.
//!
//! Both minimize the elliptic energy of Garanzha et al. 2021 (solve/untangle.h) over the
//! polycube positions with the model tets as references, every chart kept exactly on its
//! plane (labeled_mesh.h), and ghost tets (ghost_tets.h) keeping the boundary from folding.

#include "mapping/labeled_mesh.h"
#include "solve/untangle.h"

#include <vector>

namespace polycube::mapping {

//! Options of untangle_globally() and repair_locally().
struct UntangleMapOptions {
  solve::UntangleOptions untangle;  //!< the elliptic optimization
  double ghost_height = 0;          //!< apex height of the ghost tets (model length; 0: none)
};

//! One elliptic optimization of the polycube positions P (#V, chart coordinates exact), which
//! are updated in place; chart coordinates stay exactly shared.
solve::UntangleResult untangle_globally(const LabeledTetMesh& lm, std::vector<core::Vec3>& P,
                                        const UntangleMapOptions& options);

//! Options of repair_locally().
struct LocalRepairOptions {
  //! Untangle within these many tet rings of the failures, in turn, until one succeeds.
  std::vector<int> rings{2, 4, 8};
  //! When a ring count leaves failures, first place the chart fans that stayed flipped at
  //! concave corners on their long sweep (corner_fans.h), then untangle around them.
  bool reopen_fans = true;
};

//! Result of repair_locally().
struct LocalRepairResult {
  bool fixed = false;     //!< no failure left (no tet with det <= 0, no triangle facing away)
  int reopened_fans = 0;  //!< flipped corner fans placed on their long sweep
};

//! Repair the few failures a global untangling left: untangle only the coordinates near them,
//! chart coordinates at their current values, with a fresh ε (large ε is safe here: the fixed
//! surroundings keep the region from shrinking). P never gets more failures.
LocalRepairResult repair_locally(const LabeledTetMesh& lm, std::vector<core::Vec3>& P,
                                 const UntangleMapOptions& untangle, const LocalRepairOptions& options = {});

}  // namespace polycube::mapping
