#pragma once
//! \file scratch.h
//! \brief Folders for the files a test writes, removed when the test program ends.
//!
//! Every test program used to leave its folders in the system's temporary folder: thousands of
//! them, gigabytes, after a few hundred `make test` runs on one machine. A folder made here is
//! removed when the program exits, unless a test of the program failed (then the files stay for
//! a look, and their place is printed) or POLYCUBE_KEEP_TEST_FILES is set.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <string>
#include <unistd.h>
#include <vector>

namespace polycube::test {

namespace detail {

//! The folders made so far; removes them when the program ends (a function-local static made
//! after gtest's own UnitTest, so destroyed before it: the verdict can still be read).
class ScratchRegistry {
 public:
  static ScratchRegistry& get() {
    static ScratchRegistry r;
    return r;
  }
  void add(const std::filesystem::path& p) {
    const std::lock_guard<std::mutex> lock(mutex_);
    paths_.push_back(p);
  }
  ScratchRegistry(const ScratchRegistry&) = delete;
  ScratchRegistry& operator=(const ScratchRegistry&) = delete;
  ~ScratchRegistry() {
    const bool failed = ::testing::UnitTest::GetInstance()->failed_test_count() > 0;
    const bool keep = failed || std::getenv("POLYCUBE_KEEP_TEST_FILES") != nullptr;
    for (const auto& p : paths_) {
      if (keep) {
        std::cerr << "test files kept in " << p.string() << "\n";
        continue;
      }
      std::error_code ec;
      std::filesystem::remove_all(p, ec);
    }
  }

 private:
  ScratchRegistry() = default;
  std::mutex mutex_;
  std::vector<std::filesystem::path> paths_;
};

}  // namespace detail

//! A fresh, empty folder `<temp>/<name>_<pid>` (the pid: ctest runs a program's test cases as
//! parallel processes), removed when the program ends (see the file comment).
inline std::filesystem::path scratch_dir(const std::string& name) {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  detail::ScratchRegistry::get().add(d);
  return d;
}

}  // namespace polycube::test
