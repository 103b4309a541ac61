//! The plan at λ = 0, made beside the plan at the options' λ (see fewest_hexes.h).
#include "pipeline/fewest_hexes.h"

#include "core/errors.h"
#include "core/progress.h"
#include "pipeline/stage_steps.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace polycube::pipeline {

namespace {

//! The largest share of the boundary facets the plan at λ = 0 may pad to be tried after a plan
//! that pads them all: the thesis's selective padding adds 11–55 % of global padding's hexes.
constexpr double kFewestShare = 0.5;

//! The progress client of the candidate made beside the plan: it draws nothing (the pad stage's
//! bar is the plan's) and cancels the candidate once the plan at λ turned out selective, so that
//! a padding begun while that plan ran stops rather than keep a core and the stage waiting.
class Unwanted : public core::ProgressClient {
 public:
  explicit Unwanted(const std::atomic<int>& state) : state_(state) {}
  void begin(const std::string&) override {}
  void progress(const std::string&, double, bool) override {}
  void end(const std::string&, bool) override {}
  bool cancel_requested() override { return state_ == FewestHexesCandidate::kNotWanted; }

 private:
  const std::atomic<int>& state_;
};

bool wanted(const RunOptions& o) {
  return o.padding_fewest_too && o.padding == padding::PaddingMode::Selective && o.padding_selection.lambda > 0;
}

}  // namespace

FewestHexesCandidate::FewestHexesCandidate(const core::HexMesh& hex, const ConstructInput& in, const RunOptions& o)
    : in_(in), options_(o) {
  if (!wanted(o)) return;
  hex_ = hex;
  const std::vector<std::uint8_t> boundary = padding::boundary_selection(hex_);
  boundary_facets_ = static_cast<int>(std::count(boundary.begin(), boundary.end(), 1));
  options_.padding_selection.lambda = 0;
  // A candidate, not the user's plan: its starts (the pillow of HF's hexes) without a search,
  // which at λ = 0 rarely closes its gap within the limit on small meshes (and would then
  // depend on the machine).
  options_.padding_selection.search = false;
  started_ = true;
  beside_ = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) > 1;
  if (beside_)
    made_ = std::async(std::launch::async, [this] {
      const core::ThreadProgressClient unwanted(std::make_shared<Unwanted>(state_));
      // On this thread alone: the plan at λ is one solver on one core, which a second thread
      // of the candidate's optimization would slow down (and then its padding's optimization
      // gets the other cores when it starts).
      tbb::task_arena alone(1);
      return alone.execute([this] { return make(); });
    });
  else
    made_ = std::async(std::launch::deferred, [this] { return make(); });
}

FewestHexesCandidate::~FewestHexesCandidate() {
  state_ = kNotWanted;
  if (beside_ && made_.valid()) made_.wait();
}

void FewestHexesCandidate::planned(int selected) {
  int planning = kPlanning;
  state_.compare_exchange_strong(planning, selected == boundary_facets_ ? kEveryFacet : kNotWanted);
}

FewestHexesCandidate::Made FewestHexesCandidate::make() {
  Made m;
  m.plan = padding::plan_selective_padding(hex_, options_.padding_analysis, options_.padding_selection);
  const int selected = m.plan.selection.selected;
  if (selected == 0 || selected > kFewestShare * boundary_facets_ || state_ == kNotWanted) return m;
  m.padded = padding::pad_hex_mesh(hex_, in_.target, m.plan.selection.facets, options_.padding_options);
  return m;
}

std::optional<padding::PadResult> FewestHexesCandidate::take(const std::string& how, RunResult& r) {
  if (!started_ || r.padding_selected_facets != boundary_facets_) return std::nullopt;
  PC_REQUIRE(made_.valid(), "the fewest-hexes candidate is taken once");
  Made m = made_.get();
  record_plan(m.plan, r);
  const int selected = m.plan.selection.selected;
  if (selected > kFewestShare * boundary_facets_) {
    r.padding_fewest_hexes = fmt::format("lambda 0: {} of the {} boundary facets, not padded (more than {:.0f} %)",
                                         selected, boundary_facets_, 100 * kFewestShare);
    return std::nullopt;
  }
  if (!m.padded) return std::nullopt;  // HF empty: the plan at λ padded nothing either
  in_.distances.remember(m.padded->mesh, m.padded->distance);
  record_padding(*m.padded, how, r);
  return std::move(m.padded);
}

}  // namespace polycube::pipeline
