#include "laser_driver_node.h"

#include <spdlog/spdlog.h>

#include "rgnav/heartbeat_t.hpp"

namespace rgnav::drivers::sick {

LaserDriverNode::LaserDriverNode(runtime::Node& node, LaserDriverOptions options)
    : node_(node), options_(std::move(options)), driver_(options_.driver)
{
  const auto& m = options_.mounting;
  spdlog::info("laser '{}' on {} → {} (mounted at x={} y={} z={} yaw={})", options_.sensor, options_.driver.port,
               options_.channel, m.x_m, m.y_m, m.z_m, m.yaw_rad);
  node_.watch_fd([this] { return driver_.fd(); }, [this] { service(); });
  node_.every(std::chrono::milliseconds(20), [this] { service(); });
  node_.every(std::chrono::milliseconds(200), [this] { update_status(); });
  update_status();
}

void LaserDriverNode::service()
{
  for (const auto& scan : driver_.service()) {
    const auto msg = to_laser_scan_msg(scan, options_.sensor, ids_.next(scan.scan.utime));
    if (node_.publish(options_.channel, msg)) ++published_;
  }
}

void LaserDriverNode::update_status()
{
  const bool streaming = driver_.state() == Lms2xxDriver::State::kStreaming;
  const auto& s = driver_.stats();
  int8_t state = heartbeat_t::STATE_RUNNING;
  if (!streaming) state = s.connects == 0 ? heartbeat_t::STATE_STARTING : heartbeat_t::STATE_DEGRADED;
  node_.set_status(state, driver_.status_text());
}

}  // namespace rgnav::drivers::sick
