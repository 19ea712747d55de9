// stereo_capture: publishes STEREO_IMAGES from two cameras, a folder of recorded pairs, or the
// simulated head (source: sim, rendering the simulator's world at SIM_TRUTH's pose).
#include <CLI/CLI.hpp>

#include <filesystem>

#include "drivers/stereo/stereo_capture_node.h"
#include "runtime/process_main.h"
#ifdef RGNAV_SIM_STEREO
#include "sim/sim_stereo_feed.h"
#endif

int main(int argc, char** argv)
{
  using namespace rgnav;
  std::string world;  // --world: the simulator's world, as rgnav_sim --world (source: sim)
  return runtime::process_main(argc, argv, "stereo_capture", [&world](runtime::ProcessContext& ctx) -> std::shared_ptr<void> {
    const std::string config_dir = std::filesystem::path(ctx.config_path).parent_path().string();
    auto options = stereo::load_capture_options(ctx.config.section("capture"), ctx.config.section("channels"),
                                                runtime::default_data_dir(), config_dir.empty() ? "." : config_dir);
    if (!world.empty()) {
      options.sim.world_file = stereo::world_path(world, config_dir.empty() ? "." : config_dir);
      if (!std::filesystem::is_regular_file(options.sim.world_file))
        throw config::ConfigError("--world: no world file " + options.sim.world_file);
    }
    if (options.source != stereo::CaptureOptions::Source::kSim)
      return std::make_shared<stereo::StereoCaptureNode>(ctx.node, options, stereo::make_source(options));
#ifdef RGNAV_SIM_STEREO
    struct Sim
    {
      std::shared_ptr<sim::SimStereoFeed> feed;  // feeds the source the node owns: outlives it
      std::shared_ptr<stereo::StereoCaptureNode> node;
    };
    auto s = std::make_shared<Sim>();
    s->feed = std::make_shared<sim::SimStereoFeed>(ctx.node, options, ctx.robot.radius);
    s->node = std::make_shared<stereo::StereoCaptureNode>(ctx.node, options, s->feed->take_source());
    return s;
#else
    throw config::ConfigError(ctx.config_path + ": key 'capture.source': sim needs drivers/sim in the build");
#endif
  }, [&world](CLI::App& app) {
    app.add_option("--world", world, "the simulated head's world (source: sim): a name under worlds/ or a file; default: the config's");
  });
}
