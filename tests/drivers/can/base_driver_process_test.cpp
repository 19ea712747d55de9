// vcan_broker, drive_emulator and base_driver as separate processes: LCM over udpm inside a
// private network namespace (ctest runs this binary through tests/support/in_netns.sh), the
// CAN bus over the user-space broker. ODOMETRY must arrive at 50 Hz and follow BASE_CMD,
// stop when commands stop, stop on a second BASE_CMD source, report a lost drive process, and
// every process must exit 0 on SIGTERM.
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <fstream>
#include <optional>
#include <regex>
#include <thread>

#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "bus_watch.h"
#include "child_process.h"
#include "rgnav/odometry_t.hpp"
#include "rgnav/velocity_cmd_t.hpp"
#include "time/message_time.h"

namespace rgnav {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

// The shipped config with the bus socket moved into the test's directory.
std::string write_config(const testing::TempDir& dir, const std::string& socket)
{
  const std::string text =
      std::regex_replace(testing::read_file(std::string(RGNAV_SOURCE_DIR) + "/config/base_driver.yaml"), std::regex("virtual_bus_path: [^ \\n]+"), "virtual_bus_path: " + socket);
  const std::string path = dir.file("base_driver.yaml");
  std::ofstream(path) << text;
  return path;
}

class OdometryListener
{
 public:
  explicit OdometryListener(bus::LcmBus& bus)
  {
    bus::subscribe<odometry_t>(
        bus, "ODOMETRY",
        [this](const odometry_t& m, const bus::RawMessage&) {
          last = m;
          ++count;
        },
        &drops);
  }
  std::optional<odometry_t> last;
  int64_t count = 0;
  bus::DropCounter drops;
};

TEST(BaseDriverProcesses, OdometryFollowsBaseCmdAndSigtermExitsCleanly)
{
  RGNAV_REQUIRE_NETNS();
  testing::TempDir dir("rgnav_can_proc");
  const std::string socket = dir.file("vcan.sock");
  const std::string config = write_config(dir, socket);
  const std::string url = testing::test_udpm_url();
  const std::string bin = testing::executable_dir();

  testing::ChildOptions broker_out{dir.file("broker.out"), dir.file("broker.err"), {}, ""};
  testing::ChildOptions emu_out{dir.file("emu.out"), dir.file("emu.err"), {}, ""};
  testing::ChildOptions drv_out{dir.file("drv.out"), dir.file("drv.err"), {}, ""};
  testing::ChildProcess broker({bin + "/vcan_broker", "--path", socket}, broker_out);
  testing::ChildProcess emulator({bin + "/drive_emulator", "--path", socket}, emu_out);
  testing::ChildProcess driver({bin + "/base_driver", "--config", config, "--lcm-url", url}, drv_out);

  bus::LcmBus lcm(url);
  OdometryListener odo(lcm);
  auto pump_until = [&](const std::function<bool()>& pred, std::chrono::milliseconds limit,
                        const std::function<void()>& also = nullptr) {
    const auto t0 = Clock::now();
    while (Clock::now() - t0 < limit) {
      if (pred()) return true;
      lcm.handle(5ms);
      if (also) also();
    }
    return pred();
  };

  // Drives come up: ODOMETRY says STOPPED ("no command yet") at first.
  ASSERT_TRUE(pump_until([&] { return odo.last && odo.last->status == odometry_t::STATUS_STOPPED; }, 10000ms))
      << "no ODOMETRY; base_driver stderr:\n" << driver.stderr_text() << "\nemulator:\n" << emulator.stderr_text();
  // Wait for the drives to be enabled (heartbeat-wise the driver leaves STARTING).
  testing::HeartbeatWatch hb(url);
  ASSERT_TRUE(hb.wait_until("base_driver", 10000ms, [](const heartbeat_t& h) { return h.state == heartbeat_t::STATE_RUNNING; }))
      << driver.stderr_text();

  // 50 Hz.
  const int64_t c0 = odo.count;
  pump_until([] { return false; }, 1000ms);
  EXPECT_NEAR(static_cast<double>(odo.count - c0), 50.0, 10.0);

  int64_t seq = 0;
  auto t_cmd = Clock::now() - 1s;
  double v_cmd = 0.3;
  auto command = [&] {
    if (Clock::now() - t_cmd < 50ms) return;
    velocity_cmd_t cmd;
    cmd.utime = time::wall_utime();
    cmd.seq = ++seq;
    cmd.v = v_cmd;
    cmd.omega = 0.25;
    cmd.deadline_us = 200000;
    cmd.source = "lld";  // the owner of BASE_CMD in config/base_driver.yaml
    bus::publish(lcm, "BASE_CMD", cmd);
    t_cmd = Clock::now();
  };
  ASSERT_TRUE(pump_until([&] { return odo.last->status == odometry_t::STATUS_OK && std::fabs(odo.last->v - 0.3) < 1e-3; },
                         5000ms, command))
      << driver.stderr_text();
  EXPECT_NEAR(odo.last->omega, 0.25, 1e-3);
  pump_until([] { return false; }, 1000ms, command);
  const odometry_t moving = *odo.last;
  EXPECT_GT(moving.distance, 0.2);
  EXPECT_GT(moving.odom_from_base.theta, 0.2) << "heading integrates the steering";
  // Backwards: follows the new command.
  v_cmd = -0.2;
  ASSERT_TRUE(pump_until([&] { return std::fabs(odo.last->v + 0.2) < 1e-3; }, 3000ms, command));

  // Commands stop: deadman, controlled stop, STOPPED.
  const auto t_stop = Clock::now();
  ASSERT_TRUE(pump_until([&] { return odo.last->status == odometry_t::STATUS_STOPPED && odo.last->v == 0.0; }, 3000ms));
  std::printf("[ figures  ] processes: BASE_CMD stopped at 0.2 m/s -> ODOMETRY STOPPED with v = 0 after %lld ms\n",
              static_cast<long long>(std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - t_stop).count()));

  // A second BASE_CMD source while the owner drives: refused at its first command, the drives
  // quick-stop although the owner keeps commanding motion, and the heartbeat names both sources.
  v_cmd = 0.3;
  ASSERT_TRUE(pump_until([&] { return odo.last->status == odometry_t::STATUS_OK && std::fabs(odo.last->v - 0.3) < 1e-3; },
                         5000ms, command));
  velocity_cmd_t foreign;
  foreign.utime = time::wall_utime();
  foreign.seq = 1;
  foreign.v = 0.5;
  foreign.omega = 0.0;
  foreign.deadline_us = 200000;
  foreign.source = "teleop";
  bus::publish(lcm, "BASE_CMD", foreign);
  const auto t_foreign = Clock::now();
  std::optional<Clock::time_point> braking;
  ASSERT_TRUE(pump_until([&] {
    if (!braking && odo.last->v < 0.299) braking = Clock::now();
    return odo.last->v == 0.0;
  }, 3000ms, command)) << "still moving at " << odo.last->v << " m/s";
  const auto ms_since = [&](Clock::time_point t) {
    return static_cast<long long>(std::chrono::duration_cast<std::chrono::milliseconds>(t - t_foreign).count());
  };
  std::printf("[ figures  ] processes: a second BASE_CMD source at 0.3 m/s -> braking seen on ODOMETRY after %lld ms, "
              "v = 0 after %lld ms (quick stop)\n", ms_since(*braking), ms_since(Clock::now()));
  EXPECT_TRUE(hb.wait_until("base_driver", 2000ms, [](const heartbeat_t& h) {
    return h.state == heartbeat_t::STATE_DEGRADED && h.status.find("'teleop'") != std::string::npos &&
           h.status.find("'lld'") != std::string::npos;
  })) << "no heartbeat naming both sources";
  pump_until([] { return false; }, 1200ms);  // past base.foreign_quiet_ms: the alert clears

  // The drive process dies: base_driver reports FAULT on ODOMETRY.
  emulator.signal(SIGKILL);
  ASSERT_TRUE(pump_until([&] { return odo.last->status == odometry_t::STATUS_FAULT; }, 2000ms));
  EXPECT_TRUE(hb.wait_until("base_driver", 2000ms, [](const heartbeat_t& h) {
    return h.state == heartbeat_t::STATE_DEGRADED && h.status.find("heartbeat lost") != std::string::npos;
  }));

  // SIGTERM: clean exits.
  testing::expect_clean_stop(driver);
  testing::expect_clean_stop(broker);
  EXPECT_EQ(odo.drops.total(), 0);
}

TEST(BaseDriverProcesses, DriveEmulatorExitsCleanlyOnSigterm)
{
  testing::TempDir dir("rgnav_can_proc2");
  const std::string socket = dir.file("vcan.sock");
  const std::string bin = testing::executable_dir();
  testing::ChildProcess broker({bin + "/vcan_broker", "--path", socket}, {dir.file("b.out"), dir.file("b.err"), {}, ""});
  testing::ChildProcess emulator({bin + "/drive_emulator", "--path", socket}, {dir.file("e.out"), dir.file("e.err"), {}, ""});
  std::this_thread::sleep_for(500ms);
  ASSERT_TRUE(emulator.running()) << emulator.stderr_text();
  testing::expect_clean_stop(emulator);
  testing::expect_clean_stop(broker);
  // A bad config refuses to start with exit code 2.
  std::ofstream(dir.file("bad.yaml")) << "drives: {translation: {node_id: 0}}\n";
  const auto bad = testing::run_to_completion({bin + "/base_driver", "--config", dir.file("bad.yaml"), "--check-config"},
                                              10000ms, {dir.file("c.out"), dir.file("c.err"), {}, ""});
  EXPECT_TRUE(bad.exited && bad.code == 2) << bad.describe();
  const auto good = testing::run_to_completion(
      {bin + "/base_driver", "--config", std::string(RGNAV_SOURCE_DIR) + "/config/base_driver.yaml", "--check-config"},
      10000ms, {dir.file("g.out"), dir.file("g.err"), {}, ""});
  EXPECT_TRUE(good.clean()) << good.describe() << testing::read_file(dir.file("g.err"));
}

}  // namespace
}  // namespace rgnav
