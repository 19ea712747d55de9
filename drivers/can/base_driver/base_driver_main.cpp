// base_driver: the B21r synchro drive (translation + rotation CiA 402 drives on CAN).
// BASE_CMD -> drive velocities (deadman-guarded), encoders -> ODOMETRY at 50 Hz.
#include "base_driver/base_driver_node.h"
#include "runtime/process_main.h"

int main(int argc, char** argv)
{
  using namespace rgnav;
  return runtime::process_main(argc, argv, "base_driver", [](runtime::ProcessContext& ctx) -> std::shared_ptr<void> {
    const auto options = can::base::load_base_driver_options(ctx.config);
    const auto node_options = can::base::load_base_driver_node_options(ctx.config);
    // A config check must not need the bus: the CAN interface is opened only for real runs.
    if (ctx.node.bus().url() == "fake://") return std::make_shared<int>(0);
    auto driver = std::make_unique<can::base::BaseDriver>(options, can::base::make_can_interface(options));
    return std::make_shared<can::base::BaseDriverNode>(ctx.node, node_options, std::move(driver));
  });
}
