#include "importers/carmen_parser.h"

#include <cmath>

#include "importers/line_reader.h"
#include "importers/text_fields.h"

namespace rgnav::importers {
namespace {

int64_t seconds_to_utime(double s) { return static_cast<int64_t>(std::llround(s * 1e6)); }

bool numbers(const std::vector<std::string_view>& f, size_t from, size_t count, std::vector<double>* out,
             std::string* why)
{
  out->resize(count);
  for (size_t k = 0; k < count; ++k) {
    if (!parse_double(f[from + k], &(*out)[k])) {
      *why = "field " + std::to_string(from + k + 1) + " is not a number: '" + std::string(f[from + k]) + "'";
      return false;
    }
  }
  return true;
}

bool valid_ranges(const std::vector<double>& r, std::string* why)
{
  for (double v : r)
    if (v < 0.0) {
      *why = "negative range";
      return false;
    }
  return true;
}

// FLASER/RLASER n r1..rn x y theta odom_x odom_y odom_theta ipc_timestamp ipc_hostname logger_timestamp
bool parse_old_laser(const std::vector<std::string_view>& f, bool front, const CarmenOptions& o,
                     ImportedLog* log, std::string* why)
{
  int64_t n = 0;
  if (f.size() < 2 || !parse_int(f[1], &n) || n < 1 || n > 10000) {
    *why = "bad beam count";
    return false;
  }
  const size_t expected = 2 + static_cast<size_t>(n) + 9;
  if (f.size() != expected) {
    *why = "expected " + std::to_string(expected) + " fields for " + std::to_string(n) + " beams, got " +
           std::to_string(f.size());
    return false;
  }
  std::vector<double> ranges, tail1, tail2;
  if (!numbers(f, 2, static_cast<size_t>(n), &ranges, why) || !valid_ranges(ranges, why)) return false;
  if (!numbers(f, 2 + n, 6, &tail1, why) || !numbers(f, 2 + n + 6, 1, &tail2, why)) return false;
  const int64_t utime = seconds_to_utime(tail2[0]);
  sensors::LaserScan s;
  s.utime = utime;
  // 180 beams cover [-90, 89] deg at 1 deg; 181/361 beams cover [-90, 90] deg inclusive.
  const double fov = M_PI;
  s.angle_increment = static_cast<float>(n % 2 == 0 && !o.fov_inclusive ? fov / n : fov / (n - 1));
  s.angle_min = static_cast<float>(front ? -M_PI / 2 : M_PI / 2);
  s.range_min = 0.001f;
  s.range_max = o.old_laser_range_max;
  s.ranges.assign(ranges.begin(), ranges.end());
  if (!front) {
    log->add_rear_scan(std::move(s));
    return true;
  }
  // The pose fields hold odometry (or, in corrected logs, the corrected pose): the robot pose
  // at the scan, emitted just before it so a consumer interpolates exactly.
  log->add_odometry({utime, 0, tail1[3], tail1[4], tail1[5]});
  log->add_scan(std::move(s));
  if (o.flaser_pose_is_reference) log->add_reference({utime, 0, tail1[0], tail1[1], tail1[2]});
  return true;
}

// ODOM x y theta tv rv accel ipc_timestamp ipc_hostname logger_timestamp
bool parse_odom(const std::vector<std::string_view>& f, ImportedLog* log, std::string* why)
{
  if (f.size() != 10) {
    *why = "expected 10 fields, got " + std::to_string(f.size());
    return false;
  }
  std::vector<double> v, t;
  if (!numbers(f, 1, 6, &v, why) || !numbers(f, 7, 1, &t, why)) return false;
  log->add_odometry({seconds_to_utime(t[0]), 0, v[0], v[1], v[2]});
  return true;
}

// ROBOTLASER1 type start_angle fov resolution max_range accuracy remission_mode n r1..rn
//   m rem1..remm laser_x laser_y laser_theta robot_x robot_y robot_theta tv rv
//   forward_safety side_safety turn_axis ipc_timestamp ipc_hostname logger_timestamp
bool parse_robotlaser1(const std::vector<std::string_view>& f, const CarmenOptions& o, ImportedLog* log,
                       std::string* why)
{
  int64_t n = 0, m = 0;
  if (f.size() < 10 || !parse_int(f[8], &n) || n < 1 || n > 10000) {
    *why = "bad beam count";
    return false;
  }
  const size_t rem_at = 9 + static_cast<size_t>(n);
  if (f.size() <= rem_at || !parse_int(f[rem_at], &m) || m < 0 || m > 10000) {
    *why = "bad remission count";
    return false;
  }
  const size_t expected = rem_at + 1 + static_cast<size_t>(m) + 14;
  if (f.size() != expected) {
    *why = "expected " + std::to_string(expected) + " fields, got " + std::to_string(f.size());
    return false;
  }
  std::vector<double> head, ranges, poses, t;
  if (!numbers(f, 2, 5, &head, why) || !numbers(f, 9, static_cast<size_t>(n), &ranges, why) ||
      !valid_ranges(ranges, why))
    return false;
  const size_t pose_at = rem_at + 1 + static_cast<size_t>(m);
  if (!numbers(f, pose_at, 6, &poses, why) || !numbers(f, pose_at + 11, 1, &t, why)) return false;
  if (!(head[2] > 0.0) || !(head[3] > 0.0)) {
    *why = "non-positive angular resolution or range limit";
    return false;
  }
  const int64_t utime = seconds_to_utime(t[0]);
  sensors::LaserScan s;
  s.utime = utime;
  s.angle_min = static_cast<float>(head[0]);
  s.angle_increment = static_cast<float>(head[2]);
  s.range_min = 0.001f;
  s.range_max = static_cast<float>(head[3]);
  s.ranges.assign(ranges.begin(), ranges.end());
  log->add_odometry({utime, 0, poses[3], poses[4], poses[5]});
  log->add_scan(std::move(s));
  if (o.flaser_pose_is_reference) log->add_reference({utime, 0, poses[3], poses[4], poses[5]});
  return true;
}

}  // namespace

bool parse_carmen_line(const std::string& line, const CarmenOptions& options, ImportedLog* log,
                       std::string* why)
{
  const auto f = split_fields(line);
  if (f.empty() || f[0].front() == '#') return true;
  if (f[0] == "FLASER") return parse_old_laser(f, true, options, log, why);
  if (f[0] == "RLASER") return parse_old_laser(f, false, options, log, why);
  if (f[0] == "ODOM") return parse_odom(f, log, why);
  if (f[0] == "ROBOTLASER1") return parse_robotlaser1(f, options, log, why);
  return true;  // PARAM, NEFF, SYNC, TRUEPOS, ...: nothing the mapper uses
}

ImportedLog read_carmen(const std::string& path, const CarmenOptions& options)
{
  ImportedLog log;
  log.format = "carmen";
  LineReader reader(path);
  std::string line, why;
  while (reader.next(&line)) {
    why.clear();
    if (!parse_carmen_line(line, options, &log, &why)) log.issues.push_back({reader.line_number(), why});
  }
  record_end_of_input(reader, &log);
  return log;
}

}  // namespace rgnav::importers
