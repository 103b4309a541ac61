#include "core/log.h"

#include <spdlog/sinks/null_sink.h>

#include <mutex>

namespace polycube::core {

namespace {
std::mutex g_log_mutex;
std::shared_ptr<spdlog::logger>& slot() {
  static std::shared_ptr<spdlog::logger> l =
      std::make_shared<spdlog::logger>("polycube", std::make_shared<spdlog::sinks::null_sink_mt>());
  return l;
}
}  // namespace

spdlog::logger& logger() {
  std::lock_guard lock(g_log_mutex);
  return *slot();
}

void set_logger(std::shared_ptr<spdlog::logger> l) {
  std::lock_guard lock(g_log_mutex);
  if (!l) l = std::make_shared<spdlog::logger>("polycube", std::make_shared<spdlog::sinks::null_sink_mt>());
  slot() = std::move(l);
}

}  // namespace polycube::core
