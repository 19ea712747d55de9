#include "rgmap_pipeline.h"

#include <cmath>
#include <cstdlib>
#include <optional>

#include "gateway_detector/gateway_conversions.h"
#include "procs/rg_kernel/laser_points.h"

namespace rgnav::rgmap_pipeline {
namespace {

// What the gateway detector makes of an ALIGNED_SCAN (msg::to_laser_scan + on_aligned).
gateway_detector::PosedScan to_posed_scan(const scan_mapper::ScanNode& n, const scan_mapper::Pose2& base_from_laser)
{
  gateway_detector::PosedScan p;
  p.scan = n.scan;
  p.map_from_base = n.map_from_base;
  p.base_from_laser = base_from_laser;
  return p;
}

// What the RG kernel makes of an ALIGNED_SCAN (rg_kernel_conversions' to_input).
rg_kernel::ScanInput to_kernel_input(const scan_mapper::ScanNode& n, const scan_mapper::Pose2& base_from_laser)
{
  rg_kernel::ScanInput in;
  const auto& s = n.scan;
  in.scan_id = s.scan_id;
  in.utime = s.utime;
  in.revision = n.revision;
  in.map_from_base = n.map_from_base;
  in.base_from_laser = base_from_laser;
  in.laser_points = rg_kernel::laser_points(s);
  return in;
}

rg_kernel::GatewayEventInput to_kernel_event(const gateway_detector::GatewayEvent& e, int64_t utime, int64_t scan_id)
{
  rg_kernel::GatewayEventInput in;
  in.utime = utime;
  in.scan_id = scan_id;
  in.kind = static_cast<rg_kernel::GatewayEventInput::Kind>(static_cast<int>(e.kind));
  in.track_id = e.track_id;
  // Through the message class values (gateway_hypothesis_t::CLASS_*), which rgmap::GatewayClass shares.
  in.cls = static_cast<rgmap::GatewayClass>(gateway_detector::to_class_msg(e.gateway_class));
  in.map_from_base = e.map_from_base;
  in.gateway_points = e.gateway_points;
  in.direction = geometry::normalize_angle(e.direction);
  return in;
}

}  // namespace

RgMapPipeline::RgMapPipeline(const PipelineOptions& options, gateway_detector::HmmClassifier classifier)
    : options_(options),
      mapper_(options.mapper),
      detector_(options.detector, std::move(classifier)),
      kernel_(options.kernel)
{
}

void RgMapPipeline::add_odometry(const scan_mapper::OdometrySample& sample)
{
  if (options_.poses_as_given) last_odometry_ = sample;
  else mapper_.add_odometry(sample);
}

void RgMapPipeline::add_scan(const sensors::LaserScan& scan)
{
  ++counts_.scans_in;
  if (options_.poses_as_given) {
    add_given_pose_scan(scan);
    return;
  }
  const auto up = mapper_.add_scan(scan);
  if (!up.accepted) return;
  const auto& nodes = mapper_.nodes();
  // As scan_mapper_node publishes them: the corrected earlier scans first, then the new one.
  for (int i : up.corrected) correct(nodes[static_cast<size_t>(i)]);
  pass_on(nodes[static_cast<size_t>(up.node)]);
}

void RgMapPipeline::add_given_pose_scan(const sensors::LaserScan& scan)
{
  ++given_stats_.scans_in;
  // The newest pose before the scan in input order: recorded logs put the pose of each scan
  // right before it (CARMEN's FLASER pose fields, see importers/carmen_parser.cpp), and their
  // time stamps can be too coarse to interpolate by (belgioioso: 6 significant digits).
  const std::optional<scan_mapper::Pose2> odom =
      last_odometry_ && std::llabs(scan.utime - last_odometry_->utime) <= options_.mapper.max_odometry_extrapolation_us
          ? std::optional<scan_mapper::Pose2>(last_odometry_->odom_from_base)
          : std::nullopt;
  if (!odom) {
    ++given_stats_.no_odometry;
    return;
  }
  if (!given_.empty()) {
    const auto d = scan_mapper::between(given_.back().odom_from_base, *odom);
    if (scan_mapper::translation_norm(d) < options_.mapper.min_travel_m && std::fabs(d.theta()) < options_.mapper.min_rotation_rad)
      return;
  }
  scan_mapper::ScanNode n;
  n.scan = scan;
  n.odom_from_base = *odom;
  n.map_from_base = *odom;
  n.published = *odom;
  given_.push_back(std::move(n));
  ++given_stats_.accepted;
  pass_on(given_.back());
}

void RgMapPipeline::correct(const scan_mapper::ScanNode& node)
{
  ++counts_.corrections;
  if (kernel_.add_scan(to_kernel_input(node, options_.mapper.base_from_laser))) ++counts_.kernel_changes;
}

void RgMapPipeline::pass_on(const scan_mapper::ScanNode& node)
{
  ++counts_.aligned;
  const auto& mount = options_.mapper.base_from_laser;
  if (kernel_.add_scan(to_kernel_input(node, mount))) ++counts_.kernel_changes;
  last_aligned_ = node;
  const auto out = detector_.process(to_posed_scan(node, mount));
  for (const auto& e : out.events) {
    ++counts_.events;
    if (e.kind == gateway_detector::EventKind::kTraversed) ++counts_.traversals;
    if (kernel_.add_gateway_event(to_kernel_event(e, out.utime, out.scan_id))) ++counts_.kernel_changes;
  }
  last_detection_ = out;
}

std::vector<scan_mapper::ScanNode> RgMapPipeline::nodes() const
{
  return options_.poses_as_given ? given_ : mapper_.nodes();
}

scan_mapper::MapperStats RgMapPipeline::mapper_stats() const
{
  return options_.poses_as_given ? given_stats_ : mapper_.stats();
}

}  // namespace rgnav::rgmap_pipeline
