#include "gateway_detector/gateway_detector_node.h"

#include <spdlog/spdlog.h>

#include "config/string_fields.h"
#include "gateway_detector/gateway_conversions.h"
#include "msg/conversions.h"
#include "rgnav/heartbeat_t.hpp"

namespace rgnav::gateway_detector {

namespace {
constexpr size_t kOdometryHistory = 400;
constexpr size_t kScanHistory = 600;
}  // namespace

NodeChannels load_node_channels(const config::Config& c)
{
  NodeChannels n;
  n.input = c.choice("input", n.input, {"laser", "aligned"});
  config::read_strings(c, {{"laser", &n.laser}, {"odometry", &n.odometry}, {"aligned_scan", &n.aligned_scan},
                           {"objects", &n.objects}, {"hypotheses", &n.hypotheses}, {"events", &n.events}});
  return n;
}

GatewayDetectorNode::GatewayDetectorNode(runtime::Node& node, GatewayDetector detector, NodeChannels channels,
                                         geometry::Pose2 base_from_laser)
    : node_(node), detector_(std::move(detector)), channels_(std::move(channels)), base_from_laser_(base_from_laser)
{
  if (channels_.input == "laser") {
    node_.subscribe<laser_scan_t>(channels_.laser, [this](const laser_scan_t& m) { on_laser(m); });
    node_.subscribe<odometry_t>(channels_.odometry, [this](const odometry_t& m) { on_odometry(m); });
  } else {
    node_.subscribe<aligned_scan_t>(channels_.aligned_scan, [this](const aligned_scan_t& m) { on_aligned(m); });
  }
  node_.subscribe<objects3d_t>(channels_.objects, [this](const objects3d_t& m) { on_objects(m); });
}

void GatewayDetectorNode::on_odometry(const odometry_t& m)
{
  if (!odometry_.empty() && m.utime <= odometry_.back().first) return;  // out of order: keep time monotonic
  odometry_.push_back({m.utime, msg::to_pose2(m.odom_from_base)});
  while (odometry_.size() > kOdometryHistory) odometry_.pop_front();
}

bool GatewayDetectorNode::odometry_at(int64_t utime, geometry::Pose2* out) const
{
  if (odometry_.empty()) return false;
  if (utime <= odometry_.front().first) {
    *out = odometry_.front().second;
    return true;
  }
  for (size_t i = 1; i < odometry_.size(); ++i) {
    if (odometry_[i].first < utime) continue;
    const auto& [t0, p0] = odometry_[i - 1];
    const auto& [t1, p1] = odometry_[i];
    const double a = static_cast<double>(utime - t0) / static_cast<double>(t1 - t0);
    const auto d = p0.between(p1);
    *out = p0 * geometry::Pose2(a * d.x(), a * d.y(), a * d.theta());
    return true;
  }
  *out = odometry_.back().second;  // newest odometry is older than the scan: hold it
  return true;
}

void GatewayDetectorNode::on_laser(const laser_scan_t& m)
{
  PosedScan s;
  s.scan = msg::to_laser_scan(m);
  s.base_from_laser = base_from_laser_;
  geometry::Pose2 odom;
  if (!odometry_at(m.utime, &odom)) {
    if (!warned_no_odometry_) spdlog::warn("no odometry on {} yet: tracking in the base frame", channels_.odometry);
    warned_no_odometry_ = true;
    node_.set_status(heartbeat_t::STATE_DEGRADED, "no odometry");
  } else if (warned_no_odometry_) {
    warned_no_odometry_ = false;
    node_.clear_status();
  }
  s.map_from_base = odom;
  process(s, odom);
}

void GatewayDetectorNode::on_aligned(const aligned_scan_t& m)
{
  if (m.revision > 0) return;  // a loop-closure correction of an old scan: nothing new to see
  PosedScan s;
  s.scan = msg::to_laser_scan(m.scan);
  s.scan.scan_id = m.scan_id;
  s.scan.utime = m.utime;
  s.map_from_base = msg::to_pose2(m.map_from_base);
  s.base_from_laser = msg::to_pose2(m.base_from_laser);
  process(s, msg::to_pose2(m.odom_from_base));
}

void GatewayDetectorNode::process(const PosedScan& s, const geometry::Pose2& odom_from_base)
{
  if (s.scan.scan_id <= last_scan_id_) {
    spdlog::warn("dropping scan {}: not newer than scan {}", s.scan.scan_id, last_scan_id_);
    return;
  }
  last_scan_id_ = s.scan.scan_id;
  map_from_odom_[s.scan.scan_id] = s.map_from_base * odom_from_base.inverse();
  while (map_from_odom_.size() > kScanHistory) map_from_odom_.erase(map_from_odom_.begin());

  const DetectorOutput out = detector_.process(s);
  ++scans_;
  node_.publish(channels_.hypotheses, to_hypotheses_msg(out));
  for (const auto& e : out.events) node_.publish(channels_.events, to_event_msg(e, out.utime, out.scan_id));
}

void GatewayDetectorNode::on_objects(const objects3d_t& m)
{
  // Re-anchor by scan id (diss. 3.3.5): the correction of the scan taken at capture time, else
  // the newest one.
  geometry::Pose2 map_from_odom;
  const auto it = map_from_odom_.find(m.scan_id);
  if (it != map_from_odom_.end()) map_from_odom = it->second;
  else if (!map_from_odom_.empty()) map_from_odom = map_from_odom_.rbegin()->second;
  std::vector<Rectangle3> rects;
  for (const auto& r : m.rectangles) rects.push_back(to_rectangle(r));
  detector_.add_rectangles(m.utime, map_from_odom * msg::to_pose2(m.odom_from_base), rects);
}

}  // namespace rgnav::gateway_detector
