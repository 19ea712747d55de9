// A protocol-mode simulated run as separate processes, LCM over udpm inside a private network
// namespace (ctest runs this binary through tests/support/in_netns.sh): rgnav_sim (office
// world, --interface protocol) emulates the LMS 291 on a pty and the two CiA 402 drives on the
// virtual CAN bus; the real laser_driver and base_driver talk to them and publish LASER_FRONT
// and ODOMETRY. Checked: scans at the LMS rate that match a ray cast from SIM_TRUTH's pose,
// ODOMETRY following a BASE_CMD sequence (1 m ahead, 90 deg turn) and agreeing with SIM_TRUTH
// within the configured odometry error, stale commands stopping the robot, clean SIGTERM
// exits; and the same with an external vcan_broker. Prints the measured figures.
#include <gtest/gtest.h>

#include <filesystem>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "bus_watch.h"
#include "child_process.h"
#include "config/config.h"
#include "rgnav/heartbeat_t.hpp"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/velocity_cmd_t.hpp"
#include "sim/protocol_laser.h"
#include "sim/sim_options.h"
#include "sim/world_yaml.h"
#include "time/message_time.h"

namespace rgnav {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

std::string source_config(const std::string& name) { return std::string(RGNAV_SOURCE_DIR) + "/config/" + name; }

// A shipped config with exact text replacements, written into the test's directory.
std::string copy_config(const testing::TempDir& dir, const std::string& name,
                        const std::vector<std::pair<std::string, std::string>>& edits, std::string out = "")
{
  std::string text = testing::read_file(source_config(name));
  for (const auto& [from, to] : edits) {
    const size_t at = text.find(from);
    if (at == std::string::npos) throw std::runtime_error(name + ": '" + from + "' not found");
    text.replace(at, from.size(), to);
  }
  const std::string path = dir.file(out.empty() ? name : out);
  std::ofstream(path) << text;
  return path;
}

struct RunConfigs
{
  std::string sim, laser, base, socket;
};

// Every path of the run inside the test's directory: the pty symlink, the bus socket.
RunConfigs write_configs(const testing::TempDir& dir, const std::string& can_broker)
{
  RunConfigs c;
  c.socket = dir.file("vcan.sock");
  c.laser = copy_config(dir, "laser_driver_sim.yaml", {{"port: /tmp/rgnav-sim/laser_front", "port: " + dir.file("laser_front")}});
  c.base = copy_config(dir, "base_driver_sim.yaml", {{"virtual_bus_path: /tmp/rgnav-sim/vcan-base.sock", "virtual_bus_path: " + c.socket}});
  c.sim = copy_config(dir, "sim.yaml", {{"can_broker: internal", "can_broker: " + can_broker}});
  return c;
}

double normalize(double a) { return std::atan2(std::sin(a), std::cos(a)); }

// b expressed in the frame of a.
pose2d_t relative(const pose2d_t& a, const pose2d_t& b)
{
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  const double dx = b.x - a.x, dy = b.y - a.y;
  pose2d_t r;
  r.x = c * dx + s * dy;
  r.y = -s * dx + c * dy;
  r.theta = normalize(b.theta - a.theta);
  return r;
}

class Listener
{
 public:
  explicit Listener(bus::LcmBus& bus) : bus_(bus)
  {
    bus::subscribe<laser_scan_t>(bus, "LASER_FRONT", [this](const laser_scan_t& m, const bus::RawMessage&) {
      last_scan = m;
      ++scans;
      if (m.scan_id < 1'000'000'000'000) ++scans_not_from_driver;  // the driver's ids are acquisition times
      first_scan_utime = first_scan_utime ? first_scan_utime : m.utime;
      window_scans.push_back(m.utime);
    }, &drops);
    bus::subscribe<odometry_t>(bus, "ODOMETRY", [this](const odometry_t& m, const bus::RawMessage&) {
      odo = m;
      ++odometry;
      if (m.status == odometry_t::STATUS_SIMULATED) ++odometry_simulated;
    }, &drops);
    bus::subscribe<odometry_t>(bus, "SIM_TRUTH", [this](const odometry_t& m, const bus::RawMessage&) { truth = m; }, &drops);
    bus::subscribe<heartbeat_t>(bus, "HEARTBEAT", [this](const heartbeat_t& m, const bus::RawMessage&) { heartbeats[m.name] = m; }, &drops);
  }

  // Pumps until pred() holds (true) or `limit` passes (false); `also` runs every turn.
  bool pump_until(const std::function<bool()>& pred, std::chrono::milliseconds limit,
                  const std::function<void()>& also = nullptr)
  {
    const auto t0 = Clock::now();
    while (Clock::now() - t0 < limit) {
      if (pred()) return true;
      bus_.handle(5ms);
      if (also) also();
    }
    return pred();
  }
  void pump_for(std::chrono::milliseconds d, const std::function<void()>& also = nullptr)
  {
    pump_until([] { return false; }, d, also);
  }
  bool running(const std::string& name) const
  {
    const auto it = heartbeats.find(name);
    return it != heartbeats.end() && it->second.state == heartbeat_t::STATE_RUNNING;
  }
  bool standstill() const
  {
    return truth && odo && std::fabs(truth->v) < 1e-4 && std::fabs(truth->omega) < 1e-4 &&
           odo->status == odometry_t::STATUS_STOPPED && odo->v == 0.0 && odo->omega == 0.0;
  }

  std::optional<laser_scan_t> last_scan;
  int64_t scans = 0, scans_not_from_driver = 0, first_scan_utime = 0;
  std::vector<int64_t> window_scans;
  std::optional<odometry_t> odo, truth;
  int64_t odometry = 0, odometry_simulated = 0;
  std::map<std::string, heartbeat_t> heartbeats;
  bus::DropCounter drops;

 private:
  bus::LcmBus& bus_;
};

// Publishes BASE_CMD every 50 ms while called.
class Commander
{
 public:
  explicit Commander(bus::LcmBus& bus) : bus_(bus) {}
  void operator()()
  {
    if (Clock::now() - last_ < 50ms) return;
    velocity_cmd_t cmd;
    cmd.utime = time::wall_utime();
    cmd.seq = ++seq_;
    cmd.v = v;
    cmd.omega = omega;
    cmd.deadline_us = 300000;
    cmd.source = "lld";  // the owner of BASE_CMD in config/base_driver_sim.yaml
    bus::publish(bus_, "BASE_CMD", cmd);
    last_ = Clock::now();
  }
  double v = 0.0, omega = 0.0;

 private:
  bus::LcmBus& bus_;
  int64_t seq_ = 0;
  Clock::time_point last_ = Clock::now() - 1s;
};

// Fraction of the beams a ray cast from `base` predicts (hits within reach) that the scan
// reports within `tol` metres. People are left out of the cast (they walk): their beams miss.
double match_fraction(const sim::Scene& scene, const sim::World& world, const sim::Lms2xxOptions& laser,
                     const laser_scan_t& scan, const sim::Pose2& base, double tol)
{
  sim::LaserSceneState state;
  state.world_from_base = base;
  for (const auto& d : world.doors) state.door_open.push_back(d.open_at(0.0) ? 1 : 0);
  const sim::Lms2xxModel model(laser, sim::Rng(1));
  const auto expected = sim::cast_beams(scene, state, model.laser_pose(base), scan.angle_min, scan.angle_increment,
                                        scan.nranges, laser.mount_height, scan.range_max);
  int predicted = 0, matched = 0;
  for (size_t i = 0; i < expected.size(); ++i) {
    if (!std::isfinite(expected[i]) || expected[i] > scan.range_max - 0.1) continue;
    ++predicted;
    if (std::fabs(scan.ranges[i] - expected[i]) < tol) ++matched;
  }
  return predicted > 0 ? static_cast<double>(matched) / predicted : 0.0;
}

sim::Pose2 to_pose(const pose2d_t& p) { return {p.x, p.y, p.theta}; }

TEST(SimProtocolProcesses, RealDriversOnTheSimulatedB21r)
{
  RGNAV_REQUIRE_NETNS();
  testing::TempDir dir("rgnav_sim_protocol");
  const RunConfigs cfg = write_configs(dir, "internal");
  const std::string url = testing::test_udpm_url();
  const std::string bin = testing::executable_dir();
  const std::string world = source_config("worlds/office.yaml");

  bus::LcmBus lcm(url);
  Listener in(lcm);
  testing::ChildProcess simulator({bin + "/rgnav_sim", "--config", cfg.sim, "--interface", "protocol", "--world", world,
                                   "--lcm-url", url},
                                  {dir.file("sim.out"), dir.file("sim.err"), {}, ""});
  ASSERT_TRUE(in.pump_until([&] { return in.truth.has_value(); }, 20000ms))
      << "no SIM_TRUTH; rgnav_sim stderr:\n" << simulator.stderr_text();
  testing::ChildProcess laser({bin + "/laser_driver", "--config", cfg.laser, "--lcm-url", url},
                              {dir.file("laser.out"), dir.file("laser.err"), {}, ""});
  testing::ChildProcess base({bin + "/base_driver", "--config", cfg.base, "--lcm-url", url},
                             {dir.file("base.out"), dir.file("base.err"), {}, ""});
  ASSERT_TRUE(in.pump_until([&] { return in.last_scan.has_value() && in.running("base_driver") && in.odo.has_value(); },
                            20000ms))
      << "scans " << in.scans << ", odometry " << in.odometry << "\nlaser_driver:\n" << laser.stderr_text()
      << "\nbase_driver:\n" << base.stderr_text() << "\nrgnav_sim:\n" << simulator.stderr_text();

  // --- LASER_FRONT at the LMS rate, from laser_driver.
  in.window_scans.clear();
  const auto t_rate = Clock::now();
  in.pump_for(3000ms);
  const double wall_s = std::chrono::duration<double>(Clock::now() - t_rate).count();
  ASSERT_GT(in.window_scans.size(), 10u);
  const double span_s = static_cast<double>(in.window_scans.back() - in.window_scans.front()) * 1e-6;
  const double rate_stamped = static_cast<double>(in.window_scans.size() - 1) / span_s;
  const double rate_received = static_cast<double>(in.window_scans.size()) / wall_s;
  std::printf("[ figures  ] LASER_FRONT from laser_driver: %.1f Hz by scan stamps, %.1f Hz received (%d beams)\n",
              rate_stamped, rate_received, in.last_scan->nranges);
  EXPECT_EQ(in.last_scan->nranges, 181) << "laser_driver_sim.yaml: 180 deg at 1 deg";
  EXPECT_NEAR(rate_stamped, 75.0, 10.0) << "an LMS 2xx at 1 deg scans at 75 Hz";
  EXPECT_GT(rate_received, 40.0);
  EXPECT_EQ(in.scans_not_from_driver, 0) << "rgnav_sim must not publish LASER_FRONT in protocol mode";

  // --- The scans are the simulator's world seen from SIM_TRUTH's pose (standing still).
  const auto opts = sim::load_simulator_options(config::Config::load(cfg.sim),
                                               config::load_robot_description_file(source_config("robot.yaml")));
  const sim::World office = sim::load_world(world);
  const sim::Scene scene(office);
  ASSERT_TRUE(in.pump_until([&] { return in.standstill(); }, 3000ms));
  in.pump_for(100ms);
  const sim::Pose2 start = to_pose(in.truth->odom_from_base);
  const double fit = match_fraction(scene, office, opts.laser, *in.last_scan, start, 0.05);
  sim::Pose2 wrong = start;
  wrong.theta += 0.3;
  const double fit_wrong = match_fraction(scene, office, opts.laser, *in.last_scan, wrong, 0.05);
  std::printf("[ figures  ] scan vs ray cast from SIM_TRUTH: %.1f %% of beams within 5 cm (%.1f %% from a pose turned 0.3 rad)\n",
              100.0 * fit, 100.0 * fit_wrong);
  EXPECT_GT(fit, 0.85);
  EXPECT_LT(fit_wrong, 0.6);

  // --- BASE_CMD: 1 m ahead, then stale commands stop the robot.
  const odometry_t odo0 = *in.odo;
  const odometry_t truth0 = *in.truth;
  Commander cmd(lcm);
  cmd.v = 0.4;
  ASSERT_TRUE(in.pump_until([&] { return in.odo->distance - odo0.distance >= 1.0; }, 10000ms, std::ref(cmd)))
      << "ODOMETRY distance " << in.odo->distance - odo0.distance << "\n" << base.stderr_text();
  EXPECT_EQ(in.odo->status, odometry_t::STATUS_OK);
  EXPECT_NEAR(in.truth->v, 0.4, 0.02) << "the simulated base drives at the commanded speed";
  const auto t_stale = Clock::now();
  ASSERT_TRUE(in.pump_until([&] { return in.standstill(); }, 5000ms)) << "stale BASE_CMD must stop the robot";
  std::printf("[ figures  ] last BASE_CMD -> robot (SIM_TRUTH) and ODOMETRY at standstill after %lld ms\n",
              static_cast<long long>(std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - t_stale).count()));

  // --- Turn 90 deg in place.
  const double heading0 = in.odo->odom_from_base.theta;
  cmd.v = 0.0;
  cmd.omega = 0.6;
  ASSERT_TRUE(in.pump_until([&] { return normalize(in.odo->odom_from_base.theta - heading0) >= M_PI / 2; }, 10000ms,
                            std::ref(cmd)));
  ASSERT_TRUE(in.pump_until([&] { return in.standstill(); }, 5000ms));
  in.pump_for(100ms);
  const odometry_t odo1 = *in.odo;
  const odometry_t truth1 = *in.truth;

  // --- ODOMETRY (base_driver, from the simulated encoders) against SIM_TRUTH.
  const pose2d_t d_odo = relative(odo0.odom_from_base, odo1.odom_from_base);
  const pose2d_t d_true = relative(truth0.odom_from_base, truth1.odom_from_base);
  const double dist_odo = odo1.distance - odo0.distance;
  const double dist_true = truth1.distance - truth0.distance;
  const double turn_true = std::fabs(d_true.theta);
  const auto& e = opts.odometry;
  const double bound_dist = std::fabs(e.scale_translation) * dist_true + 4.0 * e.sigma_translation * std::sqrt(dist_true) + 0.02;
  const double bound_turn = std::fabs(e.scale_rotation) * turn_true + std::fabs(e.bias_rotation_per_m) * dist_true +
                            4.0 * std::sqrt(e.sigma_rotation * e.sigma_rotation * turn_true +
                                            e.sigma_rotation_per_m * e.sigma_rotation_per_m * dist_true) + 0.02;
  const double pos_err = std::hypot(d_odo.x - d_true.x, d_odo.y - d_true.y);
  std::printf("[ figures  ] drive: truth %.3f m / %.2f deg, odometry %.3f m / %.2f deg; error %.1f mm path, "
              "%.1f mm position, %.2f deg heading (bounds from sim.yaml: %.1f mm, %.2f deg)\n",
              dist_true, d_true.theta * 180 / M_PI, dist_odo, d_odo.theta * 180 / M_PI, 1000 * std::fabs(dist_odo - dist_true),
              1000 * pos_err, std::fabs(normalize(d_odo.theta - d_true.theta)) * 180 / M_PI, 1000 * bound_dist,
              bound_turn * 180 / M_PI);
  EXPECT_GT(dist_true, 0.95);
  EXPECT_GT(turn_true, 1.4);
  EXPECT_LT(std::fabs(dist_odo - dist_true), bound_dist);
  EXPECT_LT(std::fabs(normalize(d_odo.theta - d_true.theta)), bound_turn);
  EXPECT_LT(pos_err, bound_dist + dist_true * bound_turn);
  EXPECT_EQ(in.odometry_simulated, 0) << "rgnav_sim must not publish ODOMETRY in protocol mode";

  // --- The scans follow the robot: they match the new pose, not the start.
  in.pump_for(200ms);
  const double fit_end = match_fraction(scene, office, opts.laser, *in.last_scan, to_pose(in.truth->odom_from_base), 0.05);
  EXPECT_GT(fit_end, 0.85);
  EXPECT_LT(match_fraction(scene, office, opts.laser, *in.last_scan, start, 0.05), 0.6);

  // --- SIGTERM: every process exits cleanly (drivers first, then the hardware they use).
  testing::expect_clean_stop(laser);
  testing::expect_clean_stop(base);
  testing::expect_clean_stop(simulator);
  EXPECT_EQ(in.drops.total(), 0);
}

TEST(SimProtocolProcesses, ExternalBrokerAndConfigChecks)
{
  RGNAV_REQUIRE_NETNS();
  testing::TempDir dir("rgnav_sim_protocol_ext");
  const RunConfigs cfg = write_configs(dir, "external");
  const std::string url = testing::test_udpm_url();
  const std::string bin = testing::executable_dir();
  const std::string world = source_config("worlds/office.yaml");

  // Protocol mode refuses a clock the real drivers cannot follow: exit 2 naming the key.
  const std::string fast = copy_config(dir, "sim.yaml", {{"clock: realtime", "clock: fast"}}, "sim_fast.yaml");
  const auto refused = testing::run_to_completion(
      {bin + "/rgnav_sim", "--config", fast, "--interface", "protocol", "--world", world, "--check-config"}, 20000ms,
      {dir.file("fast.out"), dir.file("fast.err"), {}, ""});
  EXPECT_TRUE(refused.exited && refused.code == 2) << refused.describe();
  EXPECT_NE(testing::read_file(dir.file("fast.err")).find("sim.clock"), std::string::npos)
      << testing::read_file(dir.file("fast.err"));

  // A good config is checked without opening the emulated laser's pty (its symlink is the
  // laser driver's port) or joining the bus.
  const auto checked = testing::run_to_completion(
      {bin + "/rgnav_sim", "--config", cfg.sim, "--interface", "protocol", "--world", world, "--check-config"}, 20000ms,
      {dir.file("check.out"), dir.file("check.err"), {}, ""});
  EXPECT_TRUE(checked.exited && checked.code == 0) << checked.describe() << testing::read_file(dir.file("check.err"));
  EXPECT_FALSE(std::filesystem::exists(dir.file("laser_front"))) << "--check-config opened the emulated laser";

  bus::LcmBus lcm(url);
  Listener in(lcm);
  testing::ChildProcess broker({bin + "/vcan_broker", "--path", cfg.socket}, {dir.file("b.out"), dir.file("b.err"), {}, ""});
  testing::ChildProcess simulator({bin + "/rgnav_sim", "--config", cfg.sim, "--interface", "protocol", "--world", world,
                                   "--lcm-url", url},
                                  {dir.file("sim.out"), dir.file("sim.err"), {}, ""});
  testing::ChildProcess base({bin + "/base_driver", "--config", cfg.base, "--lcm-url", url},
                             {dir.file("base.out"), dir.file("base.err"), {}, ""});
  ASSERT_TRUE(in.pump_until([&] { return in.truth.has_value() && in.running("base_driver") && in.odo.has_value(); }, 20000ms))
      << "rgnav_sim:\n" << simulator.stderr_text() << "\nbase_driver:\n" << base.stderr_text();
  const double y0 = in.truth->odom_from_base.y;
  Commander cmd(lcm);
  cmd.v = 0.3;
  ASSERT_TRUE(in.pump_until([&] { return in.odo->distance >= 0.3; }, 5000ms, std::ref(cmd))) << base.stderr_text();
  EXPECT_GT(in.truth->odom_from_base.y - y0, 0.2) << "the office start pose faces +y";
  ASSERT_TRUE(in.pump_until([&] { return in.standstill(); }, 5000ms));

  testing::expect_clean_stop(base);
  testing::expect_clean_stop(simulator);
  testing::expect_clean_stop(broker);
}

}  // namespace
}  // namespace rgnav
