// rgnav_sim: the simulated B21r. Loads config/sim.yaml and the world, then runs the world in
// real time (or faster), standing in for the laser and base drivers: directly (it publishes
// LASER_FRONT and ODOMETRY) or, with `sim.interface: protocol` or `--interface protocol`,
// behind the hardware protocols the real laser_driver and base_driver speak.
#include <CLI/CLI.hpp>

#include <filesystem>

#include "runtime/process_main.h"
#include "sim/sim_node.h"
#include "sim/world_yaml.h"
#include "time/message_time.h"
#if RGNAV_SIM_PROTOCOL
#include "sim/protocol_hardware.h"
#endif

int main(int argc, char** argv)
{
  using namespace rgnav;
  std::string world_arg;
  std::string interface_arg;
  return runtime::process_main(
      argc, argv, "sim",
      [&](runtime::ProcessContext& ctx) -> std::shared_ptr<void> {
        auto options = sim::load_simulator_options(ctx.config, ctx.robot);
        auto process = sim::load_process_options(ctx.config.section("sim"));
        if (!interface_arg.empty())
          process.interface = interface_arg == "protocol" ? sim::InterfaceMode::kProtocol : sim::InterfaceMode::kDirect;
        sim::check_protocol_clock(process, ctx.config.section("sim"));
        const auto channels = sim::load_channels(ctx.config.section("channels"));
        const std::string config_dir = std::filesystem::path(ctx.config_path).parent_path().string();
        const auto protocol_files = sim::load_protocol_section(ctx.config.section("protocol"), config_dir);
        std::string world = world_arg.empty() ? process.world : world_arg;
        if (world_arg.empty() && std::filesystem::path(world).is_relative() && world.find('/') != std::string::npos)
          world = (std::filesystem::path(config_dir) / world).string();
        const std::string path = sim::resolve_world_path(world, config_dir + "/worlds");
        sim::SimNode::HardwareFactory hardware;
        if (process.interface == sim::InterfaceMode::kProtocol) {
#if RGNAV_SIM_PROTOCOL
          auto protocol = sim::load_protocol_options(protocol_files, ctx.config.section("protocol"), ctx.robot);
          protocol.bus_realtime_priority = process.realtime_priority;
          // --check-config validates the protocol options but opens no pseudo-terminal or bus.
          if (!ctx.checking_only)
            hardware = [protocol](sim::Simulator& s) { return std::make_unique<sim::ProtocolHardware>(protocol, s); };
          options.laser_enabled = false;  // the emulated LMS casts its own rays
#else
          (void)protocol_files;
          throw config::ConfigError(ctx.config_path + ": key 'sim.interface': protocol mode needs drivers/sick and "
                                                      "drivers/can, which this build left out");
#endif
        }
        options.start_utime = time::wall_utime();
        auto simulator = std::make_unique<sim::Simulator>(sim::load_world(path), options);
        spdlog::info("world {} from {}", simulator->world().name, path);
        return std::make_shared<sim::SimNode>(ctx.node, std::move(simulator), process, channels, false, hardware);
      },
      [&](CLI::App& app) {
        app.add_option("--world", world_arg, "world name or file (overrides sim.world)");
        app.add_option("--interface", interface_arg, "direct|protocol (overrides sim.interface)")
            ->check(CLI::IsMember({"direct", "protocol"}));
      });
}
