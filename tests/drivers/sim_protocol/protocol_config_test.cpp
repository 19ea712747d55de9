// The shipped configuration of a protocol-mode run: config/sim.yaml's `protocol` section, the
// driver configs it names, and their agreement with the real robot's driver configs and with
// the simulator's own description of the laser. The simulator reads node ids, counts per unit,
// signs, the bus socket and the laser port from the driver configs (one place); these tests
// keep the sim driver configs from drifting away from the robot's.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "can/base_driver/base_driver_options.h"
#include "config/config.h"
#include "sick/laser_driver_options.h"
#include "sim/protocol_options.h"
#include "source_paths.h"

namespace rgnav::sim {
namespace {

std::string config_dir() { return std::string(RGNAV_SOURCE_DIR) + "/config"; }
using testing::config_path;
config::RobotDescription robot() { return config::load_robot_description_file(config_path("robot.yaml")); }

// The YAML tree of a config file without the listed "section.key" entries.
std::string tree_without(const std::string& file, const std::vector<std::pair<std::string, std::string>>& drop)
{
  YAML::Node n = YAML::LoadFile(config_path(file));
  for (const auto& [section, key] : drop) {
    EXPECT_TRUE(n[section][key]) << file << ": " << section << "." << key << " missing";
    n[section].remove(key);
  }
  return YAML::Dump(n);
}

TEST(ProtocolConfig, SimDriverConfigsDifferFromTheRobotsOnlyInWhereTheHardwareIs)
{
  EXPECT_EQ(tree_without("base_driver_sim.yaml", {{"can", "virtual_bus_path"}}),
            tree_without("base_driver.yaml", {{"can", "virtual_bus_path"}}));
  EXPECT_EQ(tree_without("laser_driver_sim.yaml", {{"laser_driver", "port"}}),
            tree_without("laser_driver.yaml", {{"laser_driver", "port"}}));
}

TEST(ProtocolConfig, ShippedSimYamlServesTheSimDriverConfigs)
{
  const auto cfg = config::Config::load(config_path("sim.yaml"));
  const auto files = load_protocol_section(cfg.section("protocol"), config_dir());
  EXPECT_EQ(files.laser_driver_config, config_path("laser_driver_sim.yaml"));
  EXPECT_EQ(files.base_driver_config, config_path("base_driver_sim.yaml"));
  const ProtocolOptions p = load_protocol_options(files, cfg.section("protocol"), robot());

  const auto laser_cfg = config::Config::load(files.laser_driver_config);
  const auto laser = drivers::sick::load_laser_driver_options(laser_cfg.section("laser_driver"), laser_cfg.section("channels"), robot());
  EXPECT_EQ(p.laser_port, laser.driver.port);
  EXPECT_EQ(p.laser_port.rfind("/tmp/", 0), 0u) << "a simulated port, never a device";

  const auto base = can::base::load_base_driver_options(config::Config::load(files.base_driver_config));
  EXPECT_EQ(p.can_bus_path, base.virtual_bus_path);
  EXPECT_EQ(p.axes.translation.node_id, base.translation.node_id);
  EXPECT_EQ(p.axes.rotation.node_id, base.rotation.node_id);
  EXPECT_EQ(p.axes.translation.counts_per_unit, base.translation.counts_per_unit);
  EXPECT_EQ(p.axes.rotation.counts_per_unit, base.rotation.counts_per_unit);
  EXPECT_EQ(p.axes.translation.sign, base.translation.sign);
  EXPECT_EQ(p.axes.rotation.sign, base.rotation.sign);
  EXPECT_TRUE(files.internal_broker);
}

TEST(ProtocolConfig, TheSimulatedLaserSitsWhereTheDriverSaysItIs)
{
  const auto cfg = config::Config::load(config_path("sim.yaml"));
  const SimulatorOptions sim = load_simulator_options(cfg, robot());
  const auto laser_cfg = config::Config::load(config_path("laser_driver_sim.yaml"));
  const auto laser = drivers::sick::load_laser_driver_options(laser_cfg.section("laser_driver"), laser_cfg.section("channels"), robot());
  EXPECT_EQ(sim.laser.sensor, laser.sensor);
  EXPECT_DOUBLE_EQ(sim.laser.mount_x, laser.mounting.x_m);
  EXPECT_DOUBLE_EQ(sim.laser.mount_y, laser.mounting.y_m);
  EXPECT_DOUBLE_EQ(sim.laser.mount_yaw, laser.mounting.yaw_rad);
  EXPECT_DOUBLE_EQ(sim.laser.mount_height, laser.mounting.z_m);
  // Channels: what the simulator would publish itself is what the drivers publish.
  const auto sim_channels = cfg.section("channels");
  const auto base_cfg = config::Config::load(config_path("base_driver_sim.yaml"));
  EXPECT_EQ(sim_channels.string("laser", ""), laser.channel);
  EXPECT_EQ(sim_channels.string("odometry", ""), base_cfg.section("channels").string("odometry", ""));
  EXPECT_EQ(sim_channels.string("command", ""), base_cfg.section("channels").string("base_cmd", ""));
}

class ProtocolConfigErrors : public ::testing::Test
{
 protected:
  // base_driver_sim.yaml with `from` replaced by `to`.
  std::string variant(const std::string& name, const std::string& from, const std::string& to)
  {
    std::ifstream in(config_path("base_driver_sim.yaml"));
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return write(name, text);
  }
  std::string write(const std::string& name, const std::string& text)
  {
    const std::string path = ::testing::TempDir() + "/rgnav_proto_cfg_" + name;
    std::ofstream(path) << text;
    return path;
  }
};

TEST_F(ProtocolConfigErrors, ARealPortOrSocketCanIsRefusedNamingTheKey)
{
  const auto protocol = config::Config::parse("protocol: {}", "sim.yaml").section("protocol");
  ProtocolSection files;
  files.laser_driver_config = config_path("laser_driver.yaml");  // the robot's: /dev/ttyLMS
  files.base_driver_config = config_path("base_driver_sim.yaml");
  try {
    load_protocol_options(files, protocol, robot());
    FAIL() << "a /dev port must be refused";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("protocol.laser_driver_config"), std::string::npos) << e.what();
  }
  files.laser_driver_config = config_path("laser_driver_sim.yaml");
  files.base_driver_config = variant("socketcan.yaml", "interface: virtual", "interface: socketcan");
  try {
    load_protocol_options(files, protocol, robot());
    FAIL() << "a SocketCAN config must be refused";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("protocol.base_driver_config"), std::string::npos) << e.what();
  }
  files.base_driver_config = variant("bad_counts.yaml", "counts_per_unit: 146000", "counts_per_unit: 0");
  EXPECT_THROW(load_protocol_options(files, protocol, robot()), config::ConfigError) << "the driver's own validation applies";
}

TEST_F(ProtocolConfigErrors, ProtocolModeNeedsTheRealtimeClock)
{
  const auto sim = config::Config::parse("{world: office, interface: protocol, clock: fast}", "sim.yaml");
  ProcessOptions p = load_process_options(sim);
  ASSERT_EQ(p.interface, InterfaceMode::kProtocol);
  EXPECT_THROW(check_protocol_clock(p, sim), config::ConfigError);
  p.clock = ClockMode::kRealtime;
  p.time_scale = 2.0;
  EXPECT_THROW(check_protocol_clock(p, sim), config::ConfigError);
  p.time_scale = 1.0;
  EXPECT_NO_THROW(check_protocol_clock(p, sim));
  p.interface = InterfaceMode::kDirect;
  p.clock = ClockMode::kFast;
  EXPECT_NO_THROW(check_protocol_clock(p, sim)) << "direct mode may run fast";
}

}  // namespace
}  // namespace rgnav::sim
