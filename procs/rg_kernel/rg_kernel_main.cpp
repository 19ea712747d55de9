// rg_kernel: builds the Region & Gateway map online from aligned scans and gateway events.
#include "procs/rg_kernel/rg_kernel_node.h"
#include "runtime/process_main.h"

int main(int argc, char** argv)
{
  using namespace rgnav;
  return runtime::process_main(argc, argv, "rg_kernel", [](runtime::ProcessContext& ctx) {
    auto config = rg_kernel::load_node_config(ctx.config, runtime::default_config_dir() + "/..");
    return std::make_shared<rg_kernel::RgKernelNode>(ctx.node, config);
  });
}
