#pragma once
//! \file progress.h
//! \brief Progress reporting and cooperative cancellation (after Geogram's ProgressTask).
//!
//! Long steps create a scoped ProgressTask and call step()/set(); the installed
//! ProgressClient (the CLI's terminal bar, a GUI, or nothing) is told. A client may request
//! cancellation; the next step() then throws core::Cancelled.

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
  //! \param fraction done in [0, 1]
  virtual void progress(const std::string& task, double fraction) = 0;
  virtual void end(const std::string& task, bool ok) = 0;
  //! Polled by tasks; return true to cancel.
  virtual bool cancel_requested() { return false; }
};

//! Install the client for the whole library (nullptr: progress is ignored).
void set_progress_client(std::shared_ptr<ProgressClient> client);

//! A named long operation of a known number of steps.
class ProgressTask {
 public:
  //! \param name  what is being done ("tetrahedralize")
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
  std::string name_;
  std::int64_t total_;
  std::int64_t done_ = 0;
  int last_percent_ = -1;
  bool ok_ = false;
  std::shared_ptr<ProgressClient> client_;
};

}  // namespace polycube::core
