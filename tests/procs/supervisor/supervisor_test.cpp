// The supervisor's logic with real child processes (sleep, sh) and heartbeats fed in by the
// test. Bounds are generous: these tests check behaviour, the fault bench measures timing.
#include "supervisor.h"

#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <gtest/gtest.h>
#include <thread>

#include "child_process.h"
#include "runtime/realtime.h"
#include "proc_info.h"
#include "state_file.h"

namespace rgnav::supervisor {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

class SupervisorTest : public ::testing::Test
{
 protected:
  void SetUp() override
  {
    dir_ = std::filesystem::temp_directory_path() / ("rgnav_sup_test_" + std::to_string(getpid()) + "_" +
                                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    options_.heartbeat_timeout = milliseconds(300);
    options_.startup_timeout = milliseconds(3000);
    options_.hung_grace = milliseconds(200);
    options_.restart.initial_backoff = milliseconds(20);
    options_.restart.max_restarts = 3;
    options_.restart.window = milliseconds(30000);
  }

  void TearDown() override
  {
    for (pid_t pid : spawned_) {
      kill(-pid, SIGKILL);
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, WNOHANG);
    }
    std::filesystem::remove_all(dir_);
  }

  std::unique_ptr<Supervisor> make(const std::string& text)
  {
    auto plan = make_plan(parse_launch_text(text, "t.pmd"), {"/tmp", "", false});
    return std::make_unique<Supervisor>(std::move(plan), "testhost", options_, dir_.string());
  }

  // Runs the supervisor's loop (feeding heartbeats for `alive` processes) until pred holds.
  bool run_until(Supervisor& s, const std::function<bool()>& pred, milliseconds timeout,
                 const std::vector<std::string>& alive = {})
  {
    const auto until = Clock::now() + timeout;
    auto next_hb = Clock::now();
    while (Clock::now() < until) {
      const auto now = Clock::now();
      s.reap(now);
      if (now >= next_hb) {
        for (const auto& v : s.status(now))
          if (v.pid != 0 && std::find(alive.begin(), alive.end(), v.name) != alive.end())
            s.on_heartbeat(v.name, v.pid, now, true, progress_of_ ? progress_of_(v.name) : ++progress_);
        next_hb = now + milliseconds(100);
      }
      s.tick(now);
      for (const auto& v : s.status(now))
        if (v.pid != 0 && std::find(spawned_.begin(), spawned_.end(), v.pid) == spawned_.end()) spawned_.push_back(v.pid);
      if (pred()) return true;
      std::this_thread::sleep_for(milliseconds(5));
    }
    return false;
  }

  // SIGKILLs `name` and runs until it runs again under a new pid.
  bool killed_and_restarted(Supervisor& s, const std::string& name, const std::vector<std::string>& alive = {})
  {
    const pid_t old = view(s, name).pid;
    kill(old, SIGKILL);
    return run_until(s, [&] { return view(s, name).pid != 0 && view(s, name).pid != old; }, milliseconds(3000), alive);
  }

  // "b" (no heartbeat) starts once "a" runs.
  static constexpr const char* kBDependsOnA = R"(
cmd "b" { exec = "sleep 30"; heartbeat = "false"; depends = "a"; }
cmd "a" { exec = "sleep 31"; }
)";

  static ProcessView view(Supervisor& s, const std::string& name)
  {
    for (const auto& v : s.status(Clock::now()))
      if (v.name == name) return v;
    ADD_FAILURE() << "no process " << name;
    return {};
  }

  std::filesystem::path dir_;
  SupervisorOptions options_;
  std::function<int64_t(const std::string&)> progress_of_;   // the heartbeats' work counter (unset: always moving on)
  int64_t progress_ = 0;
  std::vector<pid_t> spawned_;
};

TEST_F(SupervisorTest, StartsInDependencyOrderAndRestartsOneProcessAlone)
{
  auto s = make(kBDependsOnA);
  s->start_all(Clock::now());
  // a needs a heartbeat to count as running; b waits for it.
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "a").state == ProcState::kStarting; }, milliseconds(2000)));
  EXPECT_EQ(view(*s, "b").state, ProcState::kStopped);
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "b").state == ProcState::kRunning; }, milliseconds(3000), {"a"}));
  const pid_t a = view(*s, "a").pid;
  ASSERT_TRUE(killed_and_restarted(*s, "b", {"a"}));
  EXPECT_EQ(view(*s, "b").restarts, 1);
  EXPECT_EQ(view(*s, "b").last_exit.rfind("signal 9", 0), 0u) << view(*s, "b").last_exit;
  EXPECT_EQ(view(*s, "a").pid, a);
  EXPECT_EQ(view(*s, "a").restarts, 0);
}

// A dependency the operator stopped holds nothing back: the demo stops the explorer before its
// room visits, and the scan mapper (started after it) stayed in back-off for good after a hang,
// leaving the robot without a pose.
TEST_F(SupervisorTest, ADependencyStoppedOnPurposeDoesNotHoldARestartBack)
{
  auto s = make(kBDependsOnA);
  s->start_all(Clock::now());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "b").state == ProcState::kRunning; }, milliseconds(3000), {"a"}));
  std::string why;
  ASSERT_TRUE(s->order(Order::kStop, "a", Clock::now(), &why)) << why;
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "a").state == ProcState::kStopped; }, milliseconds(3000)));
  ASSERT_TRUE(killed_and_restarted(*s, "b"));
  EXPECT_EQ(view(*s, "b").restarts, 1);
  EXPECT_EQ(view(*s, "a").state, ProcState::kStopped) << "stopped on purpose: not started again";
}

TEST_F(SupervisorTest, SilentProcessIsKilledAsHungAndRestarted)
{
  auto s = make("cmd \"h\" { exec = \"sleep 30\"; }");
  s->start_all(Clock::now());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "h").state == ProcState::kRunning; }, milliseconds(2000), {"h"}));
  const pid_t first = view(*s, "h").pid;
  kill(first, SIGSTOP);  // it would stop heartbeating; here the test simply stops feeding them
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "h").pid != 0 && view(*s, "h").pid != first; }, milliseconds(4000)));
  EXPECT_NE(view(*s, "h").last_exit.find("heartbeat timeout"), std::string::npos) << view(*s, "h").last_exit;
  EXPECT_EQ(view(*s, "h").restarts, 1);
}

TEST_F(SupervisorTest, BusyProcessThatProgressesIsKeptButOneStuckWhileBeatingIsHung)
{
  auto s = make("cmd \"w\" { exec = \"sleep 30\"; work_timeout_ms = 400; }");
  int64_t progress = 1;
  bool progressing = true;
  progress_of_ = [&](const std::string&) { return progressing ? ++progress : progress; };
  s->start_all(Clock::now());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "w").state == ProcState::kRunning; }, milliseconds(2000), {"w"}));
  const pid_t first = view(*s, "w").pid;
  // Beating and progressing for well over the work bound: busy, not hung.
  EXPECT_FALSE(run_until(*s, [&] { return view(*s, "w").pid != first; }, milliseconds(1200), {"w"}));
  // Still beating, progress stands still: a loop stuck in its work.
  progressing = false;
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "w").pid != 0 && view(*s, "w").pid != first; }, milliseconds(4000), {"w"}));
  EXPECT_NE(view(*s, "w").last_exit.find("no progress for 400 ms"), std::string::npos) << view(*s, "w").last_exit;
}

// A loop writing to a loaded disk (stress-ng --hdd beside the demo) is in a disk wait most of
// the time and leaves it for a moment between writes: sampled in such a moment, the scan mapper
// was stopped as hung 88 ms after it had been allowed the disk's time. Once the waits stop for
// its whole work bound, it is hung.
TEST_F(SupervisorTest, ALoopWaitingOnTheDiskOnAndOffIsSlowNotHung)
{
  options_.disk_wait_timeout = milliseconds(3000);
  auto s = make("cmd \"w\" { exec = \"sleep 30\"; work_timeout_ms = 400; }");
  int64_t progress = 1;
  bool progressing = true;
  progress_of_ = [&](const std::string&) { return progressing ? ++progress : progress; };
  bool writing = true;
  int reads = 0;
  s->set_thread_state_reader([&](pid_t) { return writing && ++reads % 2 == 1 ? 'D' : 'S'; });
  s->start_all(Clock::now());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "w").state == ProcState::kRunning; }, milliseconds(2000), {"w"}));
  const pid_t first = view(*s, "w").pid;
  progressing = false;
  EXPECT_FALSE(run_until(*s, [&] { return view(*s, "w").pid != first; }, milliseconds(1500), {"w"}))
      << "in a disk wait every other look, within the disk's allowance";
  writing = false;
  const auto waits_ended = Clock::now();
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "w").pid != first; }, milliseconds(1500), {"w"}));
  EXPECT_LT(Clock::now() - waits_ended, milliseconds(1000)) << "hung about a work bound after its last disk wait";
  EXPECT_NE(view(*s, "w").last_exit.find("no progress for 400 ms"), std::string::npos) << view(*s, "w").last_exit;
}

TEST_F(SupervisorTest, AGapTheWholeHostSharedBlamesNoProcess)
{
  auto s = make("cmd \"h\" { exec = \"sleep 30\"; }");
  s->start_all(Clock::now());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "h").state == ProcState::kRunning; }, milliseconds(2000), {"h"}));
  const pid_t pid = view(*s, "h").pid;
  // The host stood still for 1 s (the supervisor too): the heartbeat is 1 s old when the
  // supervisor runs again, but the gap is the host's.
  const auto after = Clock::now() + milliseconds(1000);
  s->on_host_stall(milliseconds(1000), after);
  s->tick(after);
  EXPECT_EQ(view(*s, "h").state, ProcState::kRunning);
  EXPECT_EQ(s->host_stalls().count, 1);
  EXPECT_EQ(s->host_stalls().longest, milliseconds(1000));
  // Without the stall the same gap is a hang.
  s->tick(after + milliseconds(1000));
  EXPECT_NE(view(*s, "h").state, ProcState::kRunning);
  run_until(*s, [&] { return view(*s, "h").pid != pid; }, milliseconds(3000), {"h"});
}

TEST(ProcInfo, MainThreadStateTellsRunningSleepingAndStopped)
{
  EXPECT_EQ(main_thread_state(getpid()), 'R');   // this test, reading
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    pause();
    _exit(0);
  }
  char state = '?';
  for (int i = 0; i < 200 && state != 'S'; ++i) {
    std::this_thread::sleep_for(milliseconds(5));
    state = main_thread_state(child);
  }
  EXPECT_EQ(state, 'S');
  kill(child, SIGSTOP);
  for (int i = 0; i < 200 && state != 'T'; ++i) {
    std::this_thread::sleep_for(milliseconds(5));
    state = main_thread_state(child);
  }
  EXPECT_EQ(state, 'T');
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  EXPECT_EQ(main_thread_state(child), '?');
}

TEST_F(SupervisorTest, CrashLoopIsGivenUpAndSafetyCriticalFailureHoldsTheRobot)
{
  auto s = make(R"(
cmd "lld" { exec = "false"; heartbeat = "false"; }
cmd "other" { exec = "sleep 30"; heartbeat = "false"; }
)");
  s->start_all(Clock::now());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "lld").state == ProcState::kFailed; }, milliseconds(5000)));
  EXPECT_TRUE(s->robot_held());
  EXPECT_NE(s->alert().find("lld"), std::string::npos) << s->alert();
  EXPECT_EQ(view(*s, "lld").restarts, options_.restart.max_restarts);
  EXPECT_EQ(view(*s, "lld").last_exit, "exit 1");
  EXPECT_EQ(view(*s, "other").state, ProcState::kRunning);
  EXPECT_EQ(view(*s, "other").restarts, 0);
  // Nothing restarts a failed process but an order.
  EXPECT_FALSE(run_until(*s, [&] { return view(*s, "lld").state != ProcState::kFailed; }, milliseconds(300)));
  std::string why;
  EXPECT_FALSE(s->order(Order::kStart, "nobody", Clock::now(), &why));
  EXPECT_NE(why.find("nobody"), std::string::npos);
}

TEST_F(SupervisorTest, StopEscalatesToSigkillAfterTheGracePeriod)
{
  auto s = make(R"(cmd "stubborn" { exec = "sh -c 'trap \"\" TERM INT; while :; do sleep 0.05; done'"; heartbeat = "false";
                   stop_signal = 15; stop_time_allowed = 0.3; })");
  s->start_all(Clock::now());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "stubborn").state == ProcState::kRunning; }, milliseconds(2000)));
  std::this_thread::sleep_for(milliseconds(100));  // let sh install its trap
  const auto t0 = Clock::now();
  std::string why;
  ASSERT_TRUE(s->order(Order::kStop, "stubborn", t0, &why));
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "stubborn").state == ProcState::kStopped; }, milliseconds(3000)));
  EXPECT_GE(Clock::now() - t0, milliseconds(300));
  EXPECT_EQ(view(*s, "stubborn").last_exit.rfind("signal 9", 0), 0u) << view(*s, "stubborn").last_exit;
  // An operator stop is not a failure: nothing restarts it.
  EXPECT_FALSE(run_until(*s, [&] { return view(*s, "stubborn").pid != 0; }, milliseconds(300)));
}

TEST_F(SupervisorTest, SuccessorAdoptsRunningChildrenAndNeverStartsDuplicates)
{
  const std::string text = "cmd \"keeper\" { exec = \"sleep 33\"; heartbeat = \"false\"; }";
  pid_t pid = 0;
  {
    auto first = make(text);
    first->start_all(Clock::now());
    ASSERT_TRUE(run_until(*first, [&] { return view(*first, "keeper").state == ProcState::kRunning; }, milliseconds(2000)));
    pid = view(*first, "keeper").pid;
  }  // the supervisor "dies" without stopping its children
  {
    auto second = make(text);
    second->recover(Clock::now());
    second->start_all(Clock::now());
    run_until(*second, [] { return false; }, milliseconds(200));
    EXPECT_EQ(view(*second, "keeper").pid, pid);
    EXPECT_TRUE(view(*second, "keeper").adopted);
  }
  // State file lost: the lock file still names the holder, which is adopted, not duplicated.
  std::filesystem::remove(dir_ / "supervisor.json");
  auto third = make(text);
  third->recover(Clock::now());
  third->start_all(Clock::now());
  run_until(*third, [] { return false; }, milliseconds(200));
  EXPECT_EQ(view(*third, "keeper").pid, pid);
  // An adopted child that dies is noticed (through /proc) and restarted.
  kill(pid, SIGKILL);
  ASSERT_TRUE(run_until(*third, [&] { return view(*third, "keeper").pid != 0 && view(*third, "keeper").pid != pid; }, milliseconds(3000)));
  EXPECT_FALSE(view(*third, "keeper").adopted);
}

TEST_F(SupervisorTest, AnotherInstanceHoldingTheLockBlocksTheStart)
{
  // A stranger (different command line) holds the process's lock: starting would make two owners.
  make_dirs(dir_.string());
  const auto stranger = spawn_child({"/bin/sleep", {"sleep", "34"}, {}, (dir_ / "dev.lock").string()});
  ASSERT_NE(stranger.pid, 0) << stranger.error;
  spawned_.push_back(stranger.pid);
  auto s = make("cmd \"dev\" { exec = \"sleep 35\"; heartbeat = \"false\"; }");
  s->start_all(Clock::now());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "dev").state == ProcState::kFailed; }, milliseconds(2000)));
  EXPECT_NE(view(*s, "dev").last_exit.find("pid " + std::to_string(stranger.pid)), std::string::npos) << view(*s, "dev").last_exit;
}

// The supervisor's own thread may run real-time (node.realtime_priority); what it starts does not
// inherit that: a process asks for its own real-time threads.
TEST_F(SupervisorTest, AChildRunsAtNormalPriorityWhateverTheSupervisorRunsAt)
{
  SpawnResult child;
  bool granted = false;
  std::thread spawner([&] {   // a thread of its own: the test's main thread keeps its scheduling
    runtime::request_realtime(5, false, &granted);
    if (granted) child = spawn_child({"/bin/sleep", {"sleep", "30"}, {}, ""});
  });
  spawner.join();
  if (!granted) GTEST_SKIP() << "SCHED_FIFO not permitted here: nothing to reset";
  ASSERT_NE(child.pid, 0) << child.error;
  spawned_.push_back(child.pid);
  sched_param p{};
  EXPECT_EQ(sched_getscheduler(child.pid), SCHED_OTHER);
  EXPECT_EQ(sched_getparam(child.pid, &p), 0);
  EXPECT_EQ(p.sched_priority, 0);
}

TEST_F(SupervisorTest, ShutdownStopsDependentsFirst)
{
  auto s = make(R"(
cmd "base" { exec = "sleep 36"; heartbeat = "false"; }
cmd "top" { exec = "sh -c 'trap \"sleep 0.3; exit 0\" TERM; while :; do sleep 0.05; done'"; heartbeat = "false"; depends = "base"; stop_signal = 15; }
)");
  s->start_all(Clock::now());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "top").state == ProcState::kRunning; }, milliseconds(3000)));
  std::this_thread::sleep_for(milliseconds(100));
  s->shutdown(Clock::now());
  // While top takes its time to stop, base must still be running.
  run_until(*s, [] { return false; }, milliseconds(150));
  EXPECT_EQ(view(*s, "base").state, ProcState::kRunning);
  ASSERT_TRUE(run_until(*s, [&] { return s->finished(); }, milliseconds(5000)));
}

TEST_F(SupervisorTest, LocalHeartbeatIsMatchedByPidWhateverNameTheProcessGivesItself)
{
  auto s = make("cmd \"cmd_name\" { exec = \"sleep 37\"; }");
  s->start_all(Clock::now());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "cmd_name").pid != 0; }, milliseconds(2000)));
  const pid_t pid = view(*s, "cmd_name").pid;
  // Another machine's process with that pid and name is not ours.
  s->on_heartbeat("cmd_name", pid, Clock::now(), false);
  s->tick(Clock::now());
  EXPECT_EQ(view(*s, "cmd_name").state, ProcState::kStarting);
  // Ours, under its own node name.
  s->on_heartbeat("node_name", pid, Clock::now(), true);
  s->tick(Clock::now());
  EXPECT_EQ(view(*s, "cmd_name").state, ProcState::kRunning);
}

TEST_F(SupervisorTest, FinishedOneshotIsDoneAndLetsDependentsStartButAFailedOneIsRetried)
{
  auto s = make(R"(
cmd "job" { exec = "true"; oneshot = "true"; heartbeat = "false"; }
cmd "svc" { exec = "sleep 38"; heartbeat = "false"; depends = "job"; }
cmd "bad_job" { exec = "false"; oneshot = "true"; heartbeat = "false"; }
)");
  s->start_all(Clock::now());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "svc").state == ProcState::kRunning; }, milliseconds(3000)));
  EXPECT_EQ(view(*s, "job").state, ProcState::kStopped);
  EXPECT_EQ(view(*s, "job").last_exit, "done (exit 0)");
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "bad_job").restarts >= 1; }, milliseconds(3000)));
  // The finished one stays done.
  EXPECT_FALSE(run_until(*s, [&] { return view(*s, "job").pid != 0; }, milliseconds(300)));
  EXPECT_EQ(view(*s, "job").restarts, 0);

  // A successor after a crash (the first one is simply abandoned) does not run it again...
  auto s2 = make(R"(
cmd "job" { exec = "true"; oneshot = "true"; heartbeat = "false"; }
cmd "svc" { exec = "sleep 38"; heartbeat = "false"; depends = "job"; }
)");
  s2->recover(Clock::now());
  s2->start_all(Clock::now());
  EXPECT_FALSE(run_until(*s2, [&] { return view(*s2, "job").pid != 0; }, milliseconds(300)));
  EXPECT_EQ(view(*s2, "job").last_exit, "done (exit 0)");
  // ...but after a clean shutdown the next launch does.
  s2->shutdown(Clock::now());
  ASSERT_TRUE(run_until(*s2, [&] { return s2->finished(); }, milliseconds(5000)));
  s->shutdown(Clock::now());
  run_until(*s, [&] { return s->finished(); }, milliseconds(3000));
  auto s3 = make(R"(cmd "job" { exec = "sleep 41"; oneshot = "true"; heartbeat = "false"; })");
  s3->recover(Clock::now());
  s3->start_all(Clock::now());
  EXPECT_TRUE(run_until(*s3, [&] { return view(*s3, "job").pid != 0; }, milliseconds(2000)));
}

TEST_F(SupervisorTest, RobotIsHeldWhileASafetyCriticalProcessIsDownAndReleasedWhenItRunsAgain)
{
  options_.restart.initial_backoff = milliseconds(300);
  auto s = make(R"(
cmd "lld" { exec = "sleep 39"; heartbeat = "false"; }
cmd "other" { exec = "sleep 40"; heartbeat = "false"; }
)");
  s->start_all(Clock::now());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "lld").state == ProcState::kRunning; }, milliseconds(2000)));
  EXPECT_FALSE(s->robot_held());
  // Not for an unimportant process.
  const pid_t other = view(*s, "other").pid;
  kill(other, SIGKILL);
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "other").pid != other && view(*s, "other").state != ProcState::kRunning; }, milliseconds(2000)));
  EXPECT_FALSE(s->robot_held());
  const pid_t lld = view(*s, "lld").pid;
  kill(lld, SIGKILL);
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "lld").state == ProcState::kBackoff; }, milliseconds(2000)));
  EXPECT_TRUE(s->robot_held());
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "lld").state == ProcState::kRunning; }, milliseconds(3000)));
  EXPECT_FALSE(s->robot_held());
  // An operator's stop is not a failure: nothing to hold for.
  std::string why;
  ASSERT_TRUE(s->order(Order::kStop, "lld", Clock::now(), &why)) << why;
  ASSERT_TRUE(run_until(*s, [&] { return view(*s, "lld").state == ProcState::kStopped; }, milliseconds(3000)));
  EXPECT_FALSE(s->robot_held());
}

}  // namespace
}  // namespace rgnav::supervisor
