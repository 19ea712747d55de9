#include "sim/protocol_options.h"

#include "can/base_driver/base_driver_options.h"
#include "sick/laser_driver_options.h"

namespace rgnav::sim {

ProtocolOptions load_protocol_options(const ProtocolSection& files, const config::Config& protocol,
                                      const config::RobotDescription& robot)
{
  ProtocolOptions o;
  o.files = files;
  const auto laser_cfg = config::Config::load(files.laser_driver_config);
  const auto laser =
      drivers::sick::load_laser_driver_options(laser_cfg.section("laser_driver"), laser_cfg.section("channels"), robot);
  o.laser_port = laser.driver.port;
  if (o.laser_port.rfind("/dev/", 0) == 0)
    protocol.fail("laser_driver_config", files.laser_driver_config + " names the port " + o.laser_port +
                                             " of a real scanner; the simulated one needs its own "
                                             "(e.g. /tmp/rgnav-sim/laser_front)");

  const auto base_cfg = config::Config::load(files.base_driver_config);
  const auto base = can::base::load_base_driver_options(base_cfg);
  if (base.interface != "virtual")
    protocol.fail("base_driver_config", files.base_driver_config +
                                            " uses can.interface: socketcan; the simulator serves the virtual CAN bus");
  o.can_bus_path = base.virtual_bus_path;
  o.axes.translation = base.translation;
  o.axes.rotation = base.rotation;
  return o;
}

}  // namespace rgnav::sim
