// A real rgnav runtime process (the contract subscriber) on real udpm: it publishes HEARTBEAT at
// ~5 Hz with sane fields, and SIGINT/SIGTERM make it exit 0 promptly, announcing STOPPING.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <fstream>

#include "bad_files.h"
#include "bus_watch.h"
#include "child_process.h"
#include "time/message_time.h"

namespace rgnav::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

ChildProcess start_node(const TempDir& dir, const std::string& name)
{
  ChildOptions o;
  o.stderr_path = dir.file(name + ".stderr");
  return ChildProcess({RGNAV_CONTRACT_SUBSCRIBER, "--config",
                       std::string(RGNAV_INTEGRATION_CONFIG_DIR) + "/contract_subscriber.yaml", "--lcm-url",
                       test_udpm_url(), "--name", name},
                      o);
}

std::string host_name()
{
  char buf[256] = {0};
  gethostname(buf, sizeof buf - 1);
  return buf;
}

TEST(RuntimeProcess, PublishesHeartbeatAtFiveHzWithSaneFields)
{
  RGNAV_REQUIRE_NETNS();
  TempDir dir;
  HeartbeatWatch watch(test_udpm_url());
  ChildProcess node = start_node(dir, "hb_probe");
  ASSERT_TRUE(watch.wait_for("hb_probe", seconds(20), node.pid())) << node.stderr_text();
  watch.clear();
  watch.collect(milliseconds(3000));
  const auto beats = watch.from("hb_probe");

  // 3 s at 5 Hz = 15; generous bounds so a loaded 2-core machine does not flake.
  ASSERT_GE(beats.size(), 8u);
  EXPECT_LE(beats.size(), 22u);
  const int64_t now = time::wall_utime();
  for (size_t i = 0; i < beats.size(); ++i) {
    const heartbeat_t& hb = beats[i].msg;
    EXPECT_EQ(hb.pid, node.pid());
    EXPECT_EQ(hb.host, host_name());
    // Its subscriptions are bus-level (it records raw bytes), so the runtime has no inputs to
    // wait for: RUNNING from the start, with no input age.
    EXPECT_EQ(hb.state, heartbeat_t::STATE_RUNNING) << hb.status;
    EXPECT_EQ(hb.last_input_age_us, -1);
    EXPECT_EQ(hb.messages_in, 0);
    EXPECT_EQ(hb.messages_dropped, 0);
    EXPECT_GT(hb.rss_kb, 100);
    EXPECT_GE(hb.cpu_percent, 0.f);
    EXPECT_LE(hb.cpu_percent, 100.f * static_cast<float>(sysconf(_SC_NPROCESSORS_ONLN)) + 1.f);
    EXPECT_NEAR(static_cast<double>(hb.utime), static_cast<double>(now), 30e6) << "utime is wall time";
    if (i > 0) {
      EXPECT_EQ(hb.seq, beats[i - 1].msg.seq + 1) << "heartbeats lost or reordered";
      EXPECT_GT(hb.utime, beats[i - 1].msg.utime);
    }
  }
  // The period, from the sender's own stamps: median within 150..300 ms of the nominal 200.
  std::vector<int64_t> gaps;
  for (size_t i = 1; i < beats.size(); ++i) gaps.push_back(beats[i].msg.utime - beats[i - 1].msg.utime);
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  EXPECT_GT(gaps[gaps.size() / 2], 150'000);
  EXPECT_LT(gaps[gaps.size() / 2], 300'000);
}

class RuntimeSignal : public ::testing::TestWithParam<int>
{
};

TEST_P(RuntimeSignal, ExitsZeroPromptlyAndSaysStopping)
{
  RGNAV_REQUIRE_NETNS();
  const int sig = GetParam();
  TempDir dir;
  HeartbeatWatch watch(test_udpm_url());
  ChildProcess node = start_node(dir, "sig_probe");
  ASSERT_TRUE(watch.wait_for("sig_probe", seconds(20), node.pid())) << node.stderr_text();

  ASSERT_TRUE(node.signal(sig));
  const auto status = node.wait_for(seconds(10));
  ASSERT_TRUE(status.has_value()) << "still running 10 s after signal " << sig;
  EXPECT_TRUE(status->clean()) << status->describe() << "\n" << node.stderr_text();
  // Its last word is a STOPPING heartbeat, so a supervisor knows the exit was intended.
  EXPECT_TRUE(watch.wait_until("sig_probe", seconds(5), [](const heartbeat_t& hb) {
    return hb.state == heartbeat_t::STATE_STOPPING;
  }));
}

INSTANTIATE_TEST_SUITE_P(SigintAndSigterm, RuntimeSignal, ::testing::Values(SIGINT, SIGTERM),
                         [](const auto& info) { return info.param == SIGINT ? "SIGINT" : "SIGTERM"; });

TEST(RuntimeProcess, BadConfigExitsTwo)
{
  // No network needed: a config error is refused before the bus is created.
  TempDir dir;
  {
    std::ofstream out(dir.file("bad.yaml"));
    out << "node:\n  name: x\n  heartbeat_hz: 5\n  hearbeat_typo: 1\n";
  }
  ChildOptions o;
  o.stderr_path = dir.file("stderr");
  const auto status = run_to_completion({RGNAV_CONTRACT_SUBSCRIBER, "--config", dir.file("bad.yaml"),
                                         "--lcm-url", "memq://"},
                                        seconds(20), o);
  EXPECT_TRUE(status.exited && status.code == 2) << status.describe();
  EXPECT_NE(read_file(dir.file("stderr")).find("hearbeat_typo"), std::string::npos) << read_file(dir.file("stderr"));
}

TEST(RuntimeProcess, BadRobotDescriptionExitsTwoBesideTheConfigOrByFlag)
{
  // The robot description beside the process config is the default; --robot names another.
  TempDir dir;
  {
    std::ifstream in(std::string(RGNAV_INTEGRATION_CONFIG_DIR) + "/contract_subscriber.yaml");
    std::ofstream out(dir.file("contract_subscriber.yaml"));
    out << in.rdbuf();
    std::ifstream robot_in(std::string(RGNAV_SOURCE_DIR) + "/config/robot.yaml");
    std::ofstream robot_out(dir.file("robot.yaml"));
    robot_out << robot_in.rdbuf() << "radius_typo: 1\n";
    std::ofstream other(dir.file("other_robot.yaml"));
    other << "robot: {name: b21r}\n";
  }
  ChildOptions o;
  o.stderr_path = dir.file("stderr");
  auto status = run_to_completion({RGNAV_CONTRACT_SUBSCRIBER, "--config", dir.file("contract_subscriber.yaml"),
                                   "--lcm-url", "memq://", "--check-config"},
                                  seconds(20), o);
  EXPECT_TRUE(status.exited && status.code == 2) << status.describe();
  EXPECT_NE(read_file(dir.file("stderr")).find("radius_typo"), std::string::npos) << read_file(dir.file("stderr"));
  status = run_to_completion({RGNAV_CONTRACT_SUBSCRIBER, "--config", dir.file("contract_subscriber.yaml"), "--robot",
                              dir.file("other_robot.yaml"), "--lcm-url", "memq://", "--check-config"},
                             seconds(20), o);
  EXPECT_TRUE(status.exited && status.code == 2) << status.describe();
  EXPECT_NE(read_file(dir.file("stderr")).find("robot.radius_m"), std::string::npos) << read_file(dir.file("stderr"));
  status = run_to_completion({RGNAV_CONTRACT_SUBSCRIBER, "--config", dir.file("contract_subscriber.yaml"), "--robot",
                              std::string(RGNAV_SOURCE_DIR) + "/config/robot.yaml", "--lcm-url", "memq://", "--check-config"},
                             seconds(20), o);
  EXPECT_TRUE(status.exited && status.code == 0) << status.describe() << read_file(dir.file("stderr"));
}

// Issue 35: every process refuses to start (exit 2, the file named) on a config or robot
// description of random bytes, an empty one, or one cut off inside a key (process_main).
TEST(RuntimeProcess, ConfigOrRobotFileOfRandomBytesEmptyOrCutOffExitsTwoNamingIt)
{
  TempDir dir;
  const std::string config = read_file(std::string(RGNAV_INTEGRATION_CONFIG_DIR) + "/contract_subscriber.yaml");
  const std::string robot = read_file(std::string(RGNAV_SOURCE_DIR) + "/config/robot.yaml");
  ASSERT_NE(config.find("heartbeat_hz"), std::string::npos);
  ASSERT_NE(robot.find("max_v_mps"), std::string::npos);
  write_bytes(dir.file("good.yaml"), config);
  ChildOptions o;
  o.stderr_path = dir.file("stderr");
  const std::string robot_path = std::string(RGNAV_SOURCE_DIR) + "/config/robot.yaml";
  for (const auto& f : write_bad_files(dir.path(), "config.yaml", config, config.find("heartbeat_hz") + 4)) {
    SCOPED_TRACE("config " + f.kind);
    const auto status = run_to_completion({RGNAV_CONTRACT_SUBSCRIBER, "--config", f.path, "--robot", robot_path,
                                           "--lcm-url", "memq://", "--check-config"},
                                          seconds(20), o);
    EXPECT_TRUE(status.exited && status.code == 2) << status.describe();
    EXPECT_NE(read_file(o.stderr_path).find(f.path), std::string::npos) << read_file(o.stderr_path);
  }
  for (const auto& f : write_bad_files(dir.path(), "robot.yaml", robot, robot.find("max_v_mps") + 3)) {
    SCOPED_TRACE("robot " + f.kind);
    const auto status = run_to_completion({RGNAV_CONTRACT_SUBSCRIBER, "--config", dir.file("good.yaml"), "--robot", f.path,
                                           "--lcm-url", "memq://", "--check-config"},
                                          seconds(20), o);
    EXPECT_TRUE(status.exited && status.code == 2) << status.describe();
    EXPECT_NE(read_file(o.stderr_path).find(f.path), std::string::npos) << read_file(o.stderr_path);
  }
}

}  // namespace
}  // namespace rgnav::testing
