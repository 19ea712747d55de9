// lld: the low-level drive. Follows TRAJECTORY with a 20 Hz Lyapunov tracking loop, sends
// BASE_CMD and LLD_STATUS. --loop-stats FILE writes the control loop's timing at exit.
#include <CLI/CLI.hpp>

#include <fstream>
#include <memory>
#include <string>

#include "lld/lld_node.h"
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
    const auto s = node->loop_stats();
    node.reset();  // joins the control thread first
    std::ofstream out(path);
    out << "{\"ticks\": " << s.ticks << ", \"overruns\": " << s.overruns << ", \"jitter_p50_ms\": " << s.jitter_p50_ms
        << ", \"jitter_p99_ms\": " << s.jitter_p99_ms << ", \"jitter_max_ms\": " << s.jitter_max_ms
        << ", \"jitter_mean_ms\": " << s.jitter_mean_ms << "}\n";
  }
};

}  // namespace

int main(int argc, char** argv)
{
  std::string stats_path;
  return rgnav::runtime::process_main(
      argc, argv, "lld",
      [&](rgnav::runtime::ProcessContext& ctx) -> std::shared_ptr<void> {
        const auto options = rgnav::lld::load_lld_options(ctx.config);
        auto writer = std::make_shared<StatsWriter>();
        writer->node = std::make_shared<rgnav::lld::LldNode>(ctx.node, options);
        writer->path = stats_path;
        return writer;
      },
      [&](CLI::App& app) { app.add_option("--loop-stats", stats_path, "write control loop timing (JSON) here at exit"); });
}
