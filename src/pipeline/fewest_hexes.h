#pragma once
//! \file fewest_hexes.h
//! \brief The other end of selective padding's trade-off, made beside the plan it is weighed
//! against (internal to src/pipeline).
//!
//! Thesis §4.5.1, §4.6: the best λ depends on the shape and is found by trying λ values. When
//! the plan at the options' λ pads every boundary facet (selective padding was not selective),
//! the pad stage also tries the plan at λ = 0 (turns free, the fewest hexes), padded and
//! optimized when it pads at most half of the boundary facets (a set nearly as large saves
//! little for its turns), and keeps it where it is as good (pipeline.cpp).
//!
//! The plan at the options' λ is one solver run on one core, tens of seconds on large meshes;
//! whether the candidate is wanted is known only at its end. So, when more than one thread is
//! allowed, the candidate is made on a thread of its own from the start: its plan, then its
//! padding and optimization while the other plan still runs or once that plan padded every
//! facet. With one thread it is made when asked for. Either way it is the same mesh: the plan
//! and the optimization give the same result on any number of threads.

#include "core/types.h"
#include "padding/padding.h"
#include "pipeline/input.h"
#include "pipeline/pipeline.h"

#include <atomic>
#include <future>
#include <optional>
#include <string>

namespace polycube::pipeline {

class FewestHexesCandidate {
 public:
  //! Starts the candidate for the pad stage of `hex` (copied) when it may be wanted:
  //! RunOptions::padding_fewest_too, selective padding at a λ above 0. `in` must outlive it.
  FewestHexesCandidate(const core::HexMesh& hex, const ConstructInput& in, const RunOptions& o);
  //! Waits for the candidate's thread (telling it first that nothing more is wanted).
  ~FewestHexesCandidate();
  FewestHexesCandidate(const FewestHexesCandidate&) = delete;
  FewestHexesCandidate& operator=(const FewestHexesCandidate&) = delete;

  //! The plan at the options' λ pads `selected` facets (pad_and_record's `planned`).
  void planned(int selected);

  //! The candidate, padded and optimized, its figures recorded in `r` (a copy the caller keeps
  //! with the mesh; r.padding = how); nothing when the plan at the options' λ did not pad every
  //! boundary facet (r.padding_selected_facets), when the candidate pads nothing, or more than
  //! half of them (why in r.padding_fewest_hexes). Writes nothing. Rethrows the candidate's
  //! errors.
  std::optional<padding::PadResult> take(const std::string& how, RunResult& r);

  //! What the candidate knows of the plan at λ: still planning, it padded every facet, or it
  //! did not (or the stage is over): the candidate is not wanted, and stops.
  enum State : int { kPlanning, kEveryFacet, kNotWanted };

 private:
  struct Made {
    padding::SelectivePlan plan;
    std::optional<padding::PadResult> padded;
  };

  //! The plan at λ = 0 and, while it may be wanted, its padded mesh.
  Made make();

  core::HexMesh hex_;
  const ConstructInput& in_;
  RunOptions options_;  //!< the plan at λ = 0's
  int boundary_facets_ = 0;
  std::atomic<int> state_{kPlanning};
  bool started_ = false;
  bool beside_ = false;  //!< made on a thread of its own (else when taken)
  std::future<Made> made_;
};

}  // namespace polycube::pipeline
