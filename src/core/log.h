#pragma once
//! \file log.h
//! \brief The one injected logger of the library (ARCHITECTURE §4).
//!
//! The library never prints: it logs through logger(), which discards everything until the
//! application installs a sink with set_logger().

#include <spdlog/spdlog.h>

#include <memory>

namespace polycube::core {

//! The library's logger (a null logger unless set_logger was called).
spdlog::logger& logger();

//! Install the logger used by the whole library (nullptr restores the null logger).
void set_logger(std::shared_ptr<spdlog::logger> l);

}  // namespace polycube::core
