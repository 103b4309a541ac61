#include "core/progress.h"

#include "core/errors.h"

#include <algorithm>
#include <mutex>

namespace polycube::core {

namespace {
std::mutex g_mutex;
std::shared_ptr<ProgressClient> g_client;
}  // namespace

void set_progress_client(std::shared_ptr<ProgressClient> client) {
  std::lock_guard lock(g_mutex);
  g_client = std::move(client);
}

ProgressTask::ProgressTask(std::string name, std::int64_t total)
    : name_(std::move(name)), total_(std::max<std::int64_t>(total, 1)) {
  {
    std::lock_guard lock(g_mutex);
    client_ = g_client;
  }
  if (client_) client_->begin(name_);
}

ProgressTask::~ProgressTask() {
  if (client_) client_->end(name_, ok_);
}

void ProgressTask::set(std::int64_t done) {
  done_ = std::clamp<std::int64_t>(done, 0, total_);
  if (!client_) return;
  // Only talk to the client when the percentage changes: tasks may step millions of times.
  const int percent = static_cast<int>(100 * done_ / total_);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  if (client_->cancel_requested()) throw Cancelled();
  client_->progress(name_, static_cast<double>(done_) / static_cast<double>(total_));
}

}  // namespace polycube::core
