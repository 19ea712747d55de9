#include "laser_driver_options.h"

#include <cmath>
#include <stdexcept>

#include "config/duration_fields.h"

namespace rgnav::drivers::sick {

LaserDriverOptions load_laser_driver_options(const config::Config& c, const config::Config& channels,
                                             const config::RobotDescription& robot)
{
  LaserDriverOptions o;
  DriverOptions& d = o.driver;
  o.channel = channels.string("laser", o.channel);
  if (o.channel.empty()) channels.fail("laser", "must not be empty");
  o.sensor = c.string("sensor", o.sensor);
  if (o.sensor.empty()) c.fail("sensor", "must not be empty");
  d.port = c.required_string("port");
  const std::vector<std::string> bauds{"9600", "19200", "38400", "500000"};
  d.initial_baud = std::stoi(c.choice("initial_baud", "9600", bauds));
  d.desired_baud = std::stoi(c.choice("desired_baud", "500000", bauds));
  const double range = c.number("angular_range_deg", 180, 100, 180);
  if (range != 100 && range != 180) c.fail("angular_range_deg", "must be 100 or 180");
  const double res = c.number("angular_resolution_deg", 1.0, 0.25, 1.0);
  if (res != 1.0 && res != 0.5 && res != 0.25) c.fail("angular_resolution_deg", "must be 1, 0.5 or 0.25");
  d.variant.angle_deg = static_cast<uint16_t>(range);
  d.variant.resolution_cdeg = static_cast<uint16_t>(std::lround(res * 100));
  if (!variant_supported(d.variant)) c.fail("angular_resolution_deg", "0.25° is only available with a 100° range");
  d.units = c.choice("units", "mm", {"mm", "cm"}) == "mm" ? Units::kMillimetres : Units::kCentimetres;
  d.password = c.string("password", d.password);
  if (d.password.size() != 8) c.fail("password", "must have exactly 8 characters");
  d.reply_timeout = config::milliseconds(c, "reply_timeout_ms", d.reply_timeout, 10, 60000);
  d.detect_timeout = config::milliseconds(c, "detect_timeout_ms", d.detect_timeout, 10, 60000);
  d.config_timeout = config::milliseconds(c, "config_timeout_ms", d.config_timeout, 10, 60000);
  d.request_tries = static_cast<int>(c.integer("request_tries", d.request_tries, 1, 10));
  d.silence_timeout = config::milliseconds(c, "silence_timeout_ms", d.silence_timeout, 10, 60000);
  d.reconnect_interval = config::milliseconds(c, "reconnect_interval_ms", d.reconnect_interval, 10, 600000);
  d.transmit_delay = std::chrono::microseconds(c.integer("transmit_delay_us", 0, 0, 100000));
  const auto& mount = robot.laser_front;
  o.mounting.x_m = mount.base_from_laser.x();
  o.mounting.y_m = mount.base_from_laser.y();
  o.mounting.z_m = mount.height;
  o.mounting.yaw_rad = mount.base_from_laser.theta();
  try {
    validate(d);
  } catch (const std::invalid_argument& e) {
    c.fail("silence_timeout_ms", e.what());
  }
  return o;
}

}  // namespace rgnav::drivers::sick
