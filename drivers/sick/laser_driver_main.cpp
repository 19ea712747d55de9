// laser_driver: SICK LMS 2xx on a serial port → LASER_FRONT (laser_scan_t).
#include "laser_driver_node.h"
#include "runtime/process_main.h"

int main(int argc, char** argv)
{
  using namespace rgnav;
  return runtime::process_main(argc, argv, "laser_driver", [](runtime::ProcessContext& ctx) -> std::shared_ptr<void> {
    auto options = drivers::sick::load_laser_driver_options(ctx.config.section("laser_driver"),
                                                            ctx.config.section("channels"), ctx.robot);
    return std::make_shared<drivers::sick::LaserDriverNode>(ctx.node, std::move(options));
  });
}
