// lld: the low-level drive. Follows TRAJECTORY with a 20 Hz Lyapunov tracking loop, sends
// BASE_CMD and LLD_STATUS. --loop-stats FILE writes the control loop's timing at exit.
#include <CLI/CLI.hpp>

#include <memory>
#include <string>

#include "lld/lld_node.h"
#include "lld/loop_stats_json.h"
#include "runtime/process_main.h"

namespace {

// Writes the loop timing when the node is torn down (after the run loop ended).
struct StatsWriter
{
  std::shared_ptr<rgnav::lld::LldNode> node;
  std::string path;
  ~StatsWriter()
  {
    if (path.empty() || !node) return;
    node->stop_loop();  // final figures: the control thread has ended
    rgnav::lld::write_loop_stats(path, node->loop_stats());
  }
};

}  // namespace

int main(int argc, char** argv)
{
  std::string stats_path;
  return rgnav::runtime::process_main(
      argc, argv, "lld",
      [&](rgnav::runtime::ProcessContext& ctx) -> std::shared_ptr<void> {
        const auto options = rgnav::lld::load_lld_options(ctx.config, ctx.robot);
        auto writer = std::make_shared<StatsWriter>();
        // A config check starts no control loop (no SCHED_FIFO thread, no mlockall).
        writer->node = std::make_shared<rgnav::lld::LldNode>(ctx.node, options, /*start_thread=*/!ctx.checking_only);
        writer->path = stats_path;
        return writer;
      },
      [&](CLI::App& app) { app.add_option("--loop-stats", stats_path, "write control loop timing (JSON) here at exit"); });
}
