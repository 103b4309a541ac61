#include "core/progress.h"

#include "core/errors.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <mutex>

namespace polycube::core {

namespace {
std::mutex g_progress_mutex;
std::shared_ptr<ProgressClient> g_client;
thread_local ProgressTask* t_current = nullptr;  // the innermost task running on this thread
// ThreadProgressClient: the client of the tasks started on this thread outside any other task.
thread_local bool t_has_own_client = false;
thread_local std::shared_ptr<ProgressClient> t_own_client;
//! The least share of the outermost bar an inner task runs on: below it the task gets a bar of
//! its own (less than a percent would not move the bar).
constexpr double kLeastShare = 0.01;
}  // namespace

void set_progress_client(std::shared_ptr<ProgressClient> client) {
  std::lock_guard lock(g_progress_mutex);
  g_client = std::move(client);
}

ProgressTask::ProgressTask(std::string name, std::int64_t total)
    : name_(std::move(name)), total_(std::max<std::int64_t>(total, 1)), parent_(t_current) {
  t_current = this;
  if (parent_) {
    root_ = parent_->root_;
    outermost_ = parent_->outermost_;
    client_ = parent_->client_;
    // The parent's current step; a second inner task in the same step gets half of what the
    // first left, and so on (the parent did not say how many it runs).
    ProgressTask& p = *parent_;
    if (p.inner_step_ != p.done_) {
      p.inner_step_ = p.done_;
      p.inner_runs_ = 0;
    }
    // Start where the bar is (an earlier inner task may have stopped early).
    const double step_hi = p.outer_fraction(static_cast<double>(std::min(p.done_ + 1, p.total_)));
    lo_ = std::min(std::max(p.outer_fraction(static_cast<double>(p.done_)), root_->shown_), step_hi);
    hi_ = p.inner_runs_ == 0 ? step_hi : lo_ + 0.5 * (step_hi - lo_);
    total_known_ = p.total_known_ && p.inner_runs_ == 0;
    ++p.inner_runs_;
    if (hi_ - lo_ >= kLeastShare) return;
    // The step is full (an earlier inner task took all of it): a long task run again after it,
    // an optimization after a fallback, would leave the bar still for minutes. It gets a bar
    // of its own instead, named after the outermost task.
    // Each such bar has a name of its own, so a client starts its clock and estimate afresh.
    ProgressTask& outer = *root_->outermost_;
    ++outer.again_;
    name_ = outer.name_ + (outer.again_ == 1 ? std::string(", again") : fmt::format(", again ({})", outer.again_));
    outermost_ = &outer;
    root_ = this;
    lo_ = 0.0;
    hi_ = 1.0;
    total_known_ = true;
    if (client_) client_->begin(name_);
    return;
  }
  if (t_has_own_client) {
    client_ = t_own_client;
  } else {
    std::lock_guard lock(g_progress_mutex);
    client_ = g_client;
  }
  if (client_) client_->begin(name_);
}

ThreadProgressClient::ThreadProgressClient(std::shared_ptr<ProgressClient> client)
    : had_(t_has_own_client), previous_(std::move(t_own_client)) {
  t_has_own_client = true;
  t_own_client = std::move(client);
}

ThreadProgressClient::~ThreadProgressClient() {
  t_has_own_client = had_;
  t_own_client = std::move(previous_);
}

ProgressTask::~ProgressTask() {
  t_current = parent_;
  if (root_ == this && client_) client_->end(name_, ok_);
}

double ProgressTask::outer_fraction(double done) const {
  return lo_ + (hi_ - lo_) * done / static_cast<double>(total_);
}

void ProgressTask::set(std::int64_t done) {
  done_ = std::clamp<std::int64_t>(done, 0, total_);
  if (!client_) return;
  report(outer_fraction(static_cast<double>(done_)), total_known_);
}

void ProgressTask::report(double fraction, bool total_known) {
  ProgressTask& r = *root_;
  // Only talk to the client when the percentage grows: tasks may step millions of times, and
  // an inner task that stops early leaves the bar where it was.
  const int percent = static_cast<int>(100.0 * fraction);
  if (percent <= r.last_percent_) return;
  r.last_percent_ = percent;
  r.shown_ = fraction;
  if (client_->cancel_requested()) throw Cancelled();
  client_->progress(r.name_, fraction, total_known);
}

}  // namespace polycube::core
