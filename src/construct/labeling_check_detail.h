#pragma once
//! \file labeling_check_detail.h
//! \brief Internal to construct/: check_labeling on a prebuilt SurfaceGraph (for repair loops).

#include "construct/labeling_check.h"
#include "construct/surface_graph.h"

namespace polycube::construct::detail {

//! check_labeling() on a prebuilt graph; `with_reasons` = false skips the reason strings.
LabelingCheck check_labeling(const SurfaceGraph& g, const std::vector<int>& labels,
                             bool with_reasons = true);

//! Weighted number of defects (the quantity repair drives to zero).
int defect_count(const LabelingCheck& check);

}  // namespace polycube::construct::detail
