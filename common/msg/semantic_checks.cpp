#include "msg/semantic_checks.h"

#include <cmath>

#include "rgmap/region_name.h"

namespace rgnav::msg {
namespace {

bool no(std::string* why, const std::string& text)
{
  if (why) *why = text;
  return false;
}

constexpr double kMaxSpeedMps = 5.0;          // no command or speed limit for this robot is faster
constexpr double kMaxSegmentLengthM = 1e3;    // [m] one trajectory segment

// A pose no part of this robot's world has: beyond 10 km of its frame's origin, or turned by
// more than 100 rad (poses are anywhere in a building, headings normalised or nearly so).
bool far_pose(const pose2d_t& p) { return std::fabs(p.x) > 1e4 || std::fabs(p.y) > 1e4 || std::fabs(p.theta) > 100.0; }

}  // namespace

bool semantically_valid(const laser_scan_t& m, std::string* why)
{
  if (m.scan_id <= 0) return no(why, "laser_scan_t: scan_id must be > 0");
  if (m.nranges < 1 || m.nranges > 10000) return no(why, "laser_scan_t: nranges outside [1, 10000]");
  if (!(m.angle_increment > 0.f)) return no(why, "laser_scan_t: angle_increment must be > 0");
  if (m.angle_increment * static_cast<float>(m.nranges - 1) > 2.f * static_cast<float>(M_PI) + 1e-3f)
    return no(why, "laser_scan_t: field of view exceeds 360 deg");
  if (!(m.range_min >= 0.f) || !(m.range_max > m.range_min))
    return no(why, "laser_scan_t: need 0 <= range_min < range_max");
  if (m.nintensities != 0 && m.nintensities != m.nranges)
    return no(why, "laser_scan_t: nintensities must be 0 or nranges");
  for (float r : m.ranges)
    if (r < 0.f) return no(why, "laser_scan_t: negative range");
  return true;
}

bool semantically_valid(const odometry_t& m, std::string* why)
{
  // Collision avoidance plans from this pose: one 1e30 m away is a chain of that length.
  if (far_pose(m.odom_from_base)) return no(why, "odometry_t: pose beyond 10 km or |theta| > 100 rad");
  if (std::fabs(m.v) > kMaxSpeedMps || std::fabs(m.omega) > 10.0)
    return no(why, "odometry_t: |v| > 5 m/s or |omega| > 10 rad/s is no motion of this robot");
  return true;
}

bool semantically_valid(const velocity_cmd_t& m, std::string* why)
{
  if (m.deadline_us <= 0) return no(why, "velocity_cmd_t: deadline_us must be > 0");
  if (std::fabs(m.v) > kMaxSpeedMps || std::fabs(m.omega) > 10.0)
    return no(why, "velocity_cmd_t: |v| > 5 m/s or |omega| > 10 rad/s is no command for this robot");
  return true;
}

bool semantically_valid(const image_t& m, std::string* why)
{
  if (m.width <= 0 || m.height <= 0 || m.width > 16384 || m.height > 16384)
    return no(why, "image_t: width/height outside [1, 16384]");
  const int64_t w = m.width, h = m.height, stride = m.row_stride;
  switch (m.pixel_format) {
    case image_t::FORMAT_GRAY8:
      if (stride < w || stride * h != m.size) return no(why, "image_t: GRAY8 size != row_stride * height");
      break;
    case image_t::FORMAT_BGR8:
      if (stride < 3 * w || stride * h != m.size) return no(why, "image_t: BGR8 size != row_stride * height");
      break;
    case image_t::FORMAT_JPEG:
      if (m.size < 4 || m.data[0] != 0xFF || m.data[1] != 0xD8) return no(why, "image_t: not a JPEG");
      break;
    default:
      return no(why, "image_t: unknown pixel_format");
  }
  return true;
}

bool semantically_valid(const stereo_images_t& m, std::string* why)
{
  return semantically_valid(m.left, why) && semantically_valid(m.right, why);
}

bool semantically_valid(const obstacle_grid_t& m, std::string* why)
{
  if (!(m.resolution > 0.f)) return no(why, "obstacle_grid_t: resolution must be > 0");
  if (m.width < 0 || m.height < 0 || static_cast<int64_t>(m.width) * m.height != m.ncells)
    return no(why, "obstacle_grid_t: ncells != width * height");
  for (int8_t c : m.cells)
    if (c < -1 || c > 100) return no(why, "obstacle_grid_t: cell outside [-1, 100]");
  return true;
}

bool semantically_valid(const region_t& m, std::string* why)
{
  if (m.id <= 0) return no(why, "region_t: id must be > 0");
  const int64_t cells = static_cast<int64_t>(m.freespace_width) * m.freespace_height;
  if (m.freespace_width < 0 || m.freespace_height < 0 || (cells + 7) / 8 != m.freespace_nbytes)
    return no(why, "region_t: freespace_nbytes != ceil(width * height / 8)");
  if (m.freespace_nbytes > 0 && !(m.freespace_resolution > 0.f))
    return no(why, "region_t: freespace_resolution must be > 0");
  return true;
}

bool semantically_valid(const trajectory_t& m, std::string* why)
{
  if (!(m.a_max > 0) || !(m.omega_max > 0)) return no(why, "trajectory_t: a_max and omega_max must be > 0");
  for (const auto& s : m.segments) {
    if (s.length < 0 || !(s.v_max > 0) || s.v_end < 0)
      return no(why, "trajectory_t: segment needs length >= 0, v_max > 0, v_end >= 0");
    // Sampled along its length by whoever drives it: a segment of 1e30 m is no trajectory but a
    // loop without end (a corrupted one hung collision avoidance in the fault bench).
    if (s.length > kMaxSegmentLengthM || far_pose(s.start))
      return no(why, "trajectory_t: segment longer than 1 km or starting beyond 10 km, or |theta| > 100 rad");
  }
  return true;
}

bool semantically_valid(const nav_goal_t& m, std::string* why)
{
  if (!(m.position_tolerance > 0) || !(m.heading_tolerance > 0))
    return no(why, "nav_goal_t: tolerances must be > 0");
  if (m.region_id < 0) return no(why, "nav_goal_t: region_id must be >= 0");
  if (!m.cancel && m.region_id == 0 && m.region_name.empty())
    return no(why, "nav_goal_t: needs region_id or region_name");
  // No region has a longer name: an oversized one is refused before anyone looks it up.
  if (m.region_name.size() > rgmap::kMaxRegionNameLength) return no(why, "nav_goal_t: region_name longer than 64 characters");
  if (far_pose(m.region_from_goal)) return no(why, "nav_goal_t: goal beyond 10 km or |theta| > 100 rad");
  return true;
}

bool semantically_valid(const target_list_t& m, std::string* why)
{
  if (!(m.max_speed > 0.f) || m.max_speed > kMaxSpeedMps) return no(why, "target_list_t: max_speed outside (0, 5] m/s");
  // Collision avoidance plans a chain through them: a target 1e30 m away made it sample a line
  // of that length for ever (the fault bench's corrupted input).
  for (const auto& p : m.odom_from_target)
    if (far_pose(p)) return no(why, "target_list_t: target beyond 10 km or |theta| > 100 rad");
  return true;
}

bool semantically_valid(const aligned_scan_t& m, std::string* why)
{
  if (m.revision < 0) return no(why, "aligned_scan_t: revision must be >= 0");
  return semantically_valid(m.scan, why);
}

bool semantically_valid(const localize_request_t& m, std::string* why)
{
  if (!(m.sigma_xy >= 0) || m.sigma_xy > 100.0) return no(why, "localize_request_t: sigma_xy outside [0, 100] m");
  if (!(m.sigma_theta >= 0) || m.sigma_theta > 2 * M_PI) return no(why, "localize_request_t: sigma_theta outside [0, 2 pi] rad");
  if (m.mode == localize_request_t::MODE_POSE) {
    if (m.region_id < 0) return no(why, "localize_request_t: region_id must be >= 0");
    if (m.region_id == 0 && m.region_name.empty()) return no(why, "localize_request_t: needs region_id or region_name");
    if (far_pose(m.region_from_base)) return no(why, "localize_request_t: pose beyond 10 km or |theta| > 100 rad");
  }
  return true;
}

bool semantically_valid(const gateway_passed_t& m, std::string* why)
{
  if (m.gateway_id <= 0 || m.from_region <= 0 || m.to_region <= 0)
    return no(why, "gateway_passed_t: gateway and region ids must be > 0");
  if (!(m.distance_past >= 0)) return no(why, "gateway_passed_t: distance_past must be >= 0");
  return true;
}

bool semantically_valid(const region_name_t& m, std::string* why)
{
  if (m.region_id <= 0) return no(why, "region_name_t: region_id must be > 0");
  std::string bad;
  if (!rgmap::valid_region_name(m.name, &bad)) return no(why, "region_name_t: " + bad);
  return true;
}

bool semantically_valid(const ca_status_t& m, std::string* why)
{
  if (!(m.blocked_s >= 0)) return no(why, "ca_status_t: blocked_s must be >= 0");
  if (m.next_target < 0) return no(why, "ca_status_t: next_target must be >= 0");
  if (m.status.size() > 256) return no(why, "ca_status_t: status longer than 256 characters");
  return true;
}

bool semantically_valid(const global_path_t& m, std::string* why)
{
  if (!(m.cost >= 0)) return no(why, "global_path_t: cost must be >= 0");
  if (m.reason.size() > 1000) return no(why, "global_path_t: reason longer than 1000 characters");
  for (const auto& w : m.waypoints)
    if (w.region_id <= 0 || w.gateway_id < 0) return no(why, "global_path_t: waypoint region_id must be > 0, gateway_id >= 0");
  return true;
}

bool semantically_valid(const region_name_request_t& m, std::string* why)
{
  if (m.region_id <= 0) return no(why, "region_name_request_t: region_id must be > 0");
  if (!(m.area >= 0)) return no(why, "region_name_request_t: area must be >= 0");
  if (std::fabs(m.centroid.x) > 1e4 || std::fabs(m.centroid.y) > 1e4)
    return no(why, "region_name_request_t: centroid beyond 10 km");
  if (m.description.size() > 200) return no(why, "region_name_request_t: description longer than 200 characters");
  return true;
}

bool semantically_valid(const explorer_status_t& m, std::string* why)
{
  if (m.activity.size() > 256) return no(why, "explorer_status_t: activity longer than 256 characters");
  if (m.current_region < 0 || m.goal_id < 0 || m.goal_region < 0)
    return no(why, "explorer_status_t: current_region, goal_id and goal_region must be >= 0");
  if (!(m.current_completeness >= 0 && m.current_completeness <= 1))
    return no(why, "explorer_status_t: current_completeness outside [0, 1]");
  if (m.regions < 0 || m.complete_regions < 0 || m.complete_regions > m.regions)
    return no(why, "explorer_status_t: need 0 <= complete_regions <= regions");
  if (m.stack_pending < 0 || m.stack_done < 0 || m.stack_set_aside < 0 || m.goals_sent < 0 || m.goals_reached < 0 ||
      m.goals_failed < 0)
    return no(why, "explorer_status_t: counts must be >= 0");
  return true;
}

}  // namespace rgnav::msg
