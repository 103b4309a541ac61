// Progress: nested tasks make one bar per outermost task, which only moves forward.
#include "core/errors.h"
#include "core/progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace polycube {
namespace {

//! Records what a client is told.
struct Recorder : core::ProgressClient {
  std::vector<std::string> begun, ended;
  std::vector<std::string> task;
  std::vector<double> fraction;
  std::vector<bool> known;
  bool cancel = false;
  void begin(const std::string& t) override { begun.push_back(t); }
  void progress(const std::string& t, double f, bool k) override {
    task.push_back(t);
    fraction.push_back(f);
    known.push_back(k);
  }
  void end(const std::string& t, bool) override { ended.push_back(t); }
  bool cancel_requested() override { return cancel; }
};

//! Installs a recorder for the test's duration.
struct Installed {
  std::shared_ptr<Recorder> r = std::make_shared<Recorder>();
  Installed() { core::set_progress_client(r); }
  ~Installed() { core::set_progress_client(nullptr); }
};

void run_inner(const char* name, int total, int stop_at) {
  core::ProgressTask inner(name, total);
  for (int i = 1; i <= stop_at; ++i) inner.set(i);
  inner.finish();
}

//! Whether the client was told this fraction (to rounding).
bool told(const std::vector<double>& v, double x) {
  return std::any_of(v.begin(), v.end(), [x](double f) { return std::abs(f - x) < 1e-12; });
}

bool non_decreasing(const std::vector<double>& v) {
  for (std::size_t i = 1; i < v.size(); ++i)
    if (v[i] < v[i - 1]) return false;
  return true;
}

TEST(Progress, InnerTasksFillTheOuterTasksStepsOnOneBar) {
  Installed c;
  {
    core::ProgressTask stage("optimize", 4);
    run_inner("untangle", 10, 10);  // step 0: all of it, to 25 %
    stage.step();
    run_inner("untangle", 10, 3);   // step 1: stops early at 30 % of its step
    stage.step();
    stage.step();                   // step 2: nothing inside
    run_inner("untangle", 100, 100);
    stage.step();
    stage.finish();
  }
  const Recorder& r = *c.r;
  EXPECT_EQ(r.begun, std::vector<std::string>{"optimize"});
  EXPECT_EQ(r.ended, std::vector<std::string>{"optimize"});
  for (const std::string& t : r.task) EXPECT_EQ(t, "optimize");
  EXPECT_TRUE(non_decreasing(r.fraction));
  ASSERT_FALSE(r.fraction.empty());
  EXPECT_DOUBLE_EQ(r.fraction.back(), 1.0);
  // The first inner task ends exactly at its step's end, the second within its step.
  EXPECT_TRUE(told(r.fraction, 0.25));
  EXPECT_TRUE(told(r.fraction, 0.25 + 0.25 * 0.3));
  for (bool k : r.known) EXPECT_TRUE(k);
}

TEST(Progress, InnerTasksRunAgainInOneStepKeepMovingWithoutAnEstimate) {
  Installed c;
  {
    core::ProgressTask stage("construct", 1);
    run_inner("untangle", 10, 4);  // 0 .. 40 %
    run_inner("untangle", 10, 10);  // half of what is left: 40 .. 70 %
    run_inner("untangle", 10, 10);  // 70 .. 85 %
    stage.step();
    stage.finish();
  }
  const Recorder& r = *c.r;
  EXPECT_EQ(r.begun.size(), 1u);
  EXPECT_TRUE(non_decreasing(r.fraction));
  EXPECT_TRUE(told(r.fraction, 0.7));
  EXPECT_TRUE(told(r.fraction, 0.85));
  EXPECT_DOUBLE_EQ(r.fraction.back(), 1.0);
  EXPECT_TRUE(r.known.front());  // the first inner task had the whole step
  EXPECT_FALSE(r.known[r.known.size() - 2]);  // the third did not know its share
}

// An optimization run again after a fallback, in a stage whose one step the first run filled:
// its progress is shown on a bar of its own, from 0 to 100 %, instead of not at all.
TEST(Progress, AnInnerTaskAfterOneThatFilledItsStepGetsABarOfItsOwn) {
  Installed c;
  {
    core::ProgressTask stage("optimize", 1);
    run_inner("untangle", 10, 10);  // 0 .. 100 %
    {
      core::ProgressTask again("untangle", 4);
      run_inner("inner", 2, 2);  // the first of again's steps, on again's bar
      again.step();
      again.set(4);
      again.finish();
    }
    stage.step();
    stage.finish();
  }
  const Recorder& r = *c.r;
  EXPECT_EQ(r.begun, (std::vector<std::string>{"optimize", "optimize, again"}));
  EXPECT_EQ(r.ended, (std::vector<std::string>{"optimize, again", "optimize"}));
  std::vector<double> first, second;
  for (std::size_t i = 0; i < r.task.size(); ++i) (r.task[i] == "optimize" ? first : second).push_back(r.fraction[i]);
  EXPECT_TRUE(non_decreasing(first));
  EXPECT_TRUE(non_decreasing(second));
  ASSERT_FALSE(second.empty());
  EXPECT_TRUE(told(second, 0.25));  // the nested task filled again's first step
  EXPECT_DOUBLE_EQ(second.back(), 1.0);
  EXPECT_DOUBLE_EQ(first.back(), 1.0);
}

// Every such bar has a name of its own (a client restarts its clock and estimate for each), and
// a task nested in one of them stays on it.
TEST(Progress, EachBarOfItsOwnHasItsOwnName) {
  Installed c;
  {
    core::ProgressTask stage("construct", 1);
    run_inner("attempt", 4, 4);
    for (int k = 0; k < 3; ++k) {
      core::ProgressTask attempt("attempt", 2);
      run_inner("untangle", 3, 3);
      attempt.step();
      attempt.step();
      attempt.finish();
    }
    stage.step();
    stage.finish();
  }
  const Recorder& r = *c.r;
  EXPECT_EQ(r.begun, (std::vector<std::string>{"construct", "construct, again", "construct, again (2)",
                                               "construct, again (3)"}));
  EXPECT_EQ(r.ended, (std::vector<std::string>{"construct, again", "construct, again (2)", "construct, again (3)",
                                               "construct"}));
  for (const char* bar : {"construct, again", "construct, again (2)", "construct, again (3)"}) {
    std::vector<double> f;
    for (std::size_t i = 0; i < r.task.size(); ++i)
      if (r.task[i] == bar) f.push_back(r.fraction[i]);
    ASSERT_FALSE(f.empty()) << bar;
    EXPECT_TRUE(told(f, 0.5)) << bar;  // the nested untangling filled the attempt's first step
    EXPECT_DOUBLE_EQ(f.back(), 1.0) << bar;
  }
}

TEST(Progress, AFailedTaskEndsItsBarAndTheNextTaskIsItsOwn) {
  Installed c;
  try {
    core::ProgressTask stage("simplify", 2);
    run_inner("untangle", 4, 2);
    throw core::GeometryError("failed");
  } catch (const core::GeometryError&) {
  }
  {
    core::ProgressTask next("hexmesh", 1);
    next.step();
    next.finish();
  }
  const Recorder& r = *c.r;
  EXPECT_EQ(r.begun, (std::vector<std::string>{"simplify", "hexmesh"}));
  EXPECT_EQ(r.ended, (std::vector<std::string>{"simplify", "hexmesh"}));
  EXPECT_EQ(r.task.back(), "hexmesh");
  EXPECT_DOUBLE_EQ(r.fraction.back(), 1.0);
}

TEST(Progress, AnInnerTaskCanBeCancelled) {
  Installed c;
  core::ProgressTask stage("optimize", 2);
  core::ProgressTask inner("untangle", 10);
  inner.set(1);
  c.r->cancel = true;
  EXPECT_THROW(inner.set(2), core::Cancelled);
}

TEST(Progress, ATaskOnAThreadWithAClientOfItsOwnTalksOnlyToThatClient) {
  Installed installed;
  const auto own = std::make_shared<Recorder>();
  std::thread([&] {
    const core::ThreadProgressClient scope(own);
    core::ProgressTask beside("pad, lambda 0", 4);
    beside.set(2);
    own->cancel = true;
    EXPECT_THROW(beside.set(3), core::Cancelled);
  }).join();
  EXPECT_EQ(own->begun, std::vector<std::string>{"pad, lambda 0"});
  EXPECT_EQ(own->ended, std::vector<std::string>{"pad, lambda 0"});
  EXPECT_TRUE(told(own->fraction, 0.5));
  EXPECT_TRUE(installed.r->begun.empty());
  EXPECT_TRUE(installed.r->task.empty());

  // Without a client of its own (nullptr), the thread's tasks talk to none; and once the scope
  // is left, to the installed one again.
  std::thread([&] {
    {
      const core::ThreadProgressClient none(nullptr);
      core::ProgressTask quiet("quiet", 2);
      quiet.set(2);
      quiet.finish();
    }
    core::ProgressTask shown("shown", 2);
    shown.set(1);
    shown.finish();
  }).join();
  EXPECT_EQ(installed.r->begun, std::vector<std::string>{"shown"});
}

}  // namespace
}  // namespace polycube
