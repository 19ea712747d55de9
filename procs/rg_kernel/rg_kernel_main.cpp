// rg_kernel: builds the Region & Gateway map online from aligned scans and gateway events.
#include <CLI/CLI.hpp>

#include "procs/rg_kernel/rg_kernel_node.h"
#include "runtime/process_main.h"

int main(int argc, char** argv)
{
  using namespace rgnav;
  std::string state_dir;
  return runtime::process_main(
      argc, argv, "rg_kernel",
      [&](runtime::ProcessContext& ctx) {
        auto config = rg_kernel::load_node_config(ctx.config, ctx.robot, runtime::default_config_dir() + "/..");
        if (!state_dir.empty()) config.state_dir = state_dir;
        if (ctx.checking_only) config.state_dir.clear();  // a config check opens no journal
        return std::make_shared<rg_kernel::RgKernelNode>(ctx.node, config);
      },
      [&](CLI::App& app) { app.add_option("--state-dir", state_dir, "journal and rgmap.json folder (overrides persistence.state_dir)"); });
}
