// tour_runner: drives the robot along a world's tour — hands targets to collision avoidance,
// or (until the low-level drive runs) follows them itself. Exits 0 when the tour is done.
#include <CLI/CLI.hpp>

#include "procs/tour_runner/tour_runner_node.h"
#include "runtime/process_main.h"

int main(int argc, char** argv)
{
  using namespace rgnav;
  std::string tour_file;
  return runtime::process_main(
      argc, argv, "tour_runner",
      [&](runtime::ProcessContext& ctx) {
        auto options = tour_runner::load_options(ctx.config.section("tour"), ctx.config.section("follower"), ctx.robot,
                                                 runtime::default_config_dir());
        if (!tour_file.empty()) options.tour_file = tour_file;
        return std::make_shared<tour_runner::TourRunnerNode>(ctx.node, options,
                                                             tour_runner::load_channels(ctx.config.section("channels")));
      },
      [&](CLI::App& app) { app.add_option("--tour", tour_file, "world or tour file (overrides tour.file)"); });
}
