// planner: routes over the RG map for navigation goals. The map (RG_MAP, or a saved map with
// --map), the robot's pose (POSE / SLAM_POSE, carried by ODOMETRY), NAV_GOAL, REGION_NAME and
// CA_STATUS -> GLOBAL_PATH, TARGETS for collision avoidance.
//   planner [--config config/planner.yaml] [--map rgmap.json|DIR] [--state-file PATH]
#include <CLI/CLI.hpp>

#include "planner/planner_node.h"
#include "runtime/process_main.h"

namespace pl = rgnav::planner;

int main(int argc, char** argv)
{
  pl::PlannerFiles files;
  return rgnav::runtime::process_main(
      argc, argv, "planner",
      [&](rgnav::runtime::ProcessContext& ctx) {
        const auto config = pl::load_planner_node_config(ctx.config, ctx.robot);
        // --check-config reads no map and neither reads nor writes the saved state.
        if (ctx.checking_only) files = {};
        return std::make_shared<pl::PlannerNode>(ctx.node, config, files);
      },
      [&](CLI::App& app) {
        app.add_option("--map", files.map, "saved RG map to plan on: rgmap.json or a folder holding one (else RG_MAP)");
        app.add_option("--state-file", files.state_file, "where learned costs, region names and the running goal are saved and resumed from");
      });
}
