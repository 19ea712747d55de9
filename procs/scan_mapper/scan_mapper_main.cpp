// The scan mapper process: LASER_FRONT + ODOMETRY -> ALIGNED_SCAN + SLAM_POSE.
//   scan_mapper [--config config/scan_mapper.yaml] [--lcm-url URL] [--state-file PATH]
#include <CLI/CLI.hpp>

#include "runtime/process_main.h"
#include "scan_mapper/scan_mapper_node.h"
#include "scan_mapper/scan_mapper_options.h"

namespace sm = rgnav::scan_mapper;

int main(int argc, char** argv)
{
  std::string state_file;
  return rgnav::runtime::process_main(
      argc, argv, "scan_mapper",
      [&](rgnav::runtime::ProcessContext& ctx) {
        const auto options = sm::load_scan_mapper_options(ctx.config.section("scan_mapper"), ctx.robot);
        const auto channels = sm::load_scan_mapper_channels(ctx.config.section("channels"));
        auto persistence = sm::load_persistence_options(ctx.config.section("persistence"));
        if (!state_file.empty()) persistence.state_file = state_file;
        // --check-config must not read or write the state file.
        if (ctx.checking_only) persistence.state_file.clear();
        return std::make_shared<sm::ScanMapperNode>(ctx.node, options, channels, persistence);
      },
      [&](CLI::App& app) {
        app.add_option("--state-file", state_file, "where the mapper persists its state (overrides persistence.state_file)");
      });
}
