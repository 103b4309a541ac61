#pragma once
//! \file progress.h
//! \brief Progress reporting and cooperative cancellation (after Geogram's ProgressTask).
//!
//! Long steps create a scoped ProgressTask and call step()/set(); the installed
//! ProgressClient (the CLI's terminal bar, a GUI, or nothing) is told. A client may request
//! cancellation; the next step() then throws core::Cancelled.
//!
//! Tasks nest: a task created (on the same thread) while another runs is a part of it and
//! fills the outer task's current step, so a client sees one bar per outermost task (a stage
//! of `run`), moving only forward. An inner task that runs again within the same outer step
//! (an untangling retried, an attempt after a failed one) gets half of what is left of that
//! step each time: the bar still moves, but the total is then unknown and clients are told so
//! (no time estimate). When less than a percent of the bar is left for it (an earlier inner
//! task filled the step), it gets a bar of its own, "<outermost task>, again" (then "again (2)",
//! ...), from 0 %.

#include <cstdint>
#include <memory>
#include <string>

namespace polycube::core {

//! Receives progress of long operations. Implementations must be cheap; calls come from the
//! thread running the task.
class ProgressClient {
 public:
  virtual ~ProgressClient() = default;
  virtual void begin(const std::string& task) = 0;
  //! \param fraction    done in [0, 1], never lower than the fraction of the previous call
  //! \param total_known false when the task does not know how much is left (no estimate)
  virtual void progress(const std::string& task, double fraction, bool total_known) = 0;
  virtual void end(const std::string& task, bool ok) = 0;
  //! Polled by tasks; return true to cancel.
  virtual bool cancel_requested() { return false; }
};

//! Install the client for the whole library (nullptr: progress is ignored).
void set_progress_client(std::shared_ptr<ProgressClient> client);

//! A named long operation of a known number of steps.
class ProgressTask {
 public:
  //! \param name  what is being done ("tetrahedralize"); an inner task's name is not shown
  //! \param total number of steps (>= 1)
  ProgressTask(std::string name, std::int64_t total);
  ~ProgressTask();
  ProgressTask(const ProgressTask&) = delete;
  ProgressTask& operator=(const ProgressTask&) = delete;

  //! Advance by one step. \throw Cancelled when the client asked to cancel.
  void step() { set(done_ + 1); }
  //! Set the number of completed steps. \throw Cancelled when the client asked to cancel.
  void set(std::int64_t done);
  //! Mark success (otherwise the destructor reports the task as failed).
  void finish() { ok_ = true; }

 private:
  //! The outermost task's fraction at `done` steps of this one.
  [[nodiscard]] double outer_fraction(double done) const;
  //! Tell the client the outermost task's fraction, when its percentage grew.
  void report(double fraction, bool total_known);

  std::string name_;
  std::int64_t total_;
  std::int64_t done_ = 0;
  ProgressTask* parent_ = nullptr;  //!< the task this one is a part of (same thread)
  ProgressTask* root_ = this;       //!< the task that talks to the client (outermost, or a bar of its own)
  ProgressTask* outermost_ = this;  //!< the outermost task (its name and count of bars "again")
  int again_ = 0;                   //!< of the outermost task: inner tasks given a bar of their own
  double lo_ = 0.0, hi_ = 1.0;      //!< this task's range in the outermost task's fraction
  bool total_known_ = true;         //!< false once this task or an outer one guessed its range
  // Of the outermost task only:
  int last_percent_ = -1;
  double shown_ = 0.0;
  // Inner tasks run so far within the current step (each gets half of what is left).
  std::int64_t inner_step_ = -1;
  int inner_runs_ = 0;
  bool ok_ = false;
  std::shared_ptr<ProgressClient> client_;
};

//! While one lives, tasks started on this thread outside any other task talk to `client`
//! (nullptr: to none) instead of the installed one: work done beside a stage on a thread of
//! its own draws no bar of its own, calls no client from a second thread, and can be cancelled
//! by its owner alone.
class ThreadProgressClient {
 public:
  explicit ThreadProgressClient(std::shared_ptr<ProgressClient> client);
  ~ThreadProgressClient();
  ThreadProgressClient(const ThreadProgressClient&) = delete;
  ThreadProgressClient& operator=(const ThreadProgressClient&) = delete;

 private:
  bool had_;
  std::shared_ptr<ProgressClient> previous_;
};

}  // namespace polycube::core
