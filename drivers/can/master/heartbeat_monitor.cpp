#include "master/heartbeat_monitor.h"

namespace rgnav::can::master {

void HeartbeatMonitor::watch(uint8_t node, std::chrono::milliseconds consumer_time)
{
  nodes_[node].consumer_time = consumer_time;
}

std::optional<std::pair<uint8_t, canopen::NmtState>> HeartbeatMonitor::handle(const can_frame& f, Clock::time_point now)
{
  if (f.can_id & (CAN_EFF_FLAG | CAN_ERR_FLAG | CAN_RTR_FLAG)) return std::nullopt;
  const canid_t id = f.can_id & CAN_SFF_MASK;
  if (id <= canopen::kHeartbeat || id > canopen::kHeartbeat + 127 || f.can_dlc != 1) return std::nullopt;
  const auto node = static_cast<uint8_t>(id - canopen::kHeartbeat);
  auto it = nodes_.find(node);
  if (it == nodes_.end()) return std::nullopt;
  const auto state = canopen::nmt_state_from_byte(f.data[0]);
  if (!state) return std::nullopt;
  Entry& e = it->second;
  e.seen = true;
  e.lost = false;
  e.last = now;
  e.state = *state;
  return std::make_pair(node, *state);
}

std::vector<uint8_t> HeartbeatMonitor::tick(Clock::time_point now)
{
  std::vector<uint8_t> newly_lost;
  for (auto& [node, e] : nodes_) {
    if (!e.seen || e.lost || e.consumer_time.count() == 0) continue;
    if (now - e.last > e.consumer_time) {
      e.lost = true;
      newly_lost.push_back(node);
    }
  }
  return newly_lost;
}

bool HeartbeatMonitor::lost(uint8_t node) const
{
  const auto it = nodes_.find(node);
  return it != nodes_.end() && it->second.lost;
}

bool HeartbeatMonitor::seen(uint8_t node) const
{
  const auto it = nodes_.find(node);
  return it != nodes_.end() && it->second.seen;
}

std::optional<canopen::NmtState> HeartbeatMonitor::state(uint8_t node) const
{
  const auto it = nodes_.find(node);
  if (it == nodes_.end() || !it->second.seen) return std::nullopt;
  return it->second.state;
}

void HeartbeatMonitor::reset()
{
  for (auto& [node, e] : nodes_) {
    e.seen = false;
    e.lost = false;
  }
}

}  // namespace rgnav::can::master
