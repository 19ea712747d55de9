// explorer: explores an unknown building region by region through the planner. RG_MAP, POSE /
// SLAM_POSE, GATEWAY_HYPOTHESES and GLOBAL_PATH -> NAV_GOAL, REGION_NAME_REQUEST, EXPLORER_STATUS.
//   explorer [--config config/explorer.yaml] [--state-file PATH]
#include <CLI/CLI.hpp>

#include "explorer/explorer_node.h"
#include "runtime/process_main.h"

namespace ex = rgnav::explorer;

int main(int argc, char** argv)
{
  ex::ExplorerFiles files;
  return rgnav::runtime::process_main(
      argc, argv, "explorer",
      [&](rgnav::runtime::ProcessContext& ctx) {
        const auto config = ex::load_explorer_node_config(ctx.config, ctx.robot, ctx.config_path);
        // --check-config neither reads nor writes the saved state.
        if (ctx.checking_only) files = {};
        return std::make_shared<ex::ExplorerNode>(ctx.node, config, files);
      },
      [&](CLI::App& app) {
        app.add_option("--state-file", files.state_file,
                       "where the gateway stack, visited frontiers and phase are saved and resumed from");
      });
}
