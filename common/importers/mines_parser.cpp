#include "importers/mines_parser.h"

#include <cmath>
#include <optional>

#include "importers/line_reader.h"
#include "importers/text_fields.h"

namespace rgnav::importers {
namespace {

struct Ticks
{
  int64_t left = 0, right = 0;
};

}  // namespace

ImportedLog read_mines(const std::string& path, const MinesOptions& o)
{
  ImportedLog log;
  log.format = "mines";
  LineReader reader(path);
  std::string line;
  std::optional<Ticks> prev;
  std::optional<size_t> beams;  // every line of a log has the same count
  PoseRecord pose;
  const double m_per_tick = 2.0 * M_PI * o.wheel_radius_m / o.ticks_per_turn;
  while (reader.next(&line)) {
    const auto f = split_fields(line);
    if (f.empty()) continue;
    const auto bad = [&](const std::string& why) { log.issues.push_back({reader.line_number(), why}); };
    if (f.size() <= static_cast<size_t>(o.first_range_field) + 2 * o.margin_beams) {
      bad("expected at least " + std::to_string(o.first_range_field + 2 * o.margin_beams + 1) +
          " fields, got " + std::to_string(f.size()));
      continue;
    }
    const size_t n = f.size() - static_cast<size_t>(o.first_range_field);
    if (beams && *beams != n) {
      bad("expected " + std::to_string(*beams) + " ranges like the lines before, got " + std::to_string(n));
      continue;
    }
    int64_t utime = 0;
    Ticks t;
    if (!parse_int(f[0], &utime) || !parse_int(f[2], &t.left) || !parse_int(f[3], &t.right)) {
      bad("timestamp or wheel ticks are not integers");
      continue;
    }
    if (!log.scans.empty() && utime <= log.scans.back().utime) {
      bad("timestamp does not increase");
      continue;
    }
    sensors::LaserScan s;
    s.utime = utime;
    s.ranges.resize(n);
    bool ok = true;
    for (size_t k = 0; k < n && ok; ++k) {
      int64_t mm = 0;
      ok = parse_int(f[static_cast<size_t>(o.first_range_field) + k], &mm) && mm >= 0;
      const bool margin = k < static_cast<size_t>(o.margin_beams) || k + static_cast<size_t>(o.margin_beams) >= n;
      s.ranges[k] = margin ? 0.f : static_cast<float>(mm) * 1e-3f;
    }
    if (!ok) {
      bad("a range is not a non-negative integer");
      continue;
    }
    beams = n;
    const double inc = o.angle_increment_deg * M_PI / 180.0;
    s.angle_increment = static_cast<float>(inc);
    s.angle_min = static_cast<float>(-0.5 * inc * static_cast<double>(n - 1));
    s.range_min = o.range_min_m;
    s.range_max = o.range_max_m;
    s.scan_time = 0.1f;
    if (prev) {
      // Differential drive, midpoint integration of one step.
      const double dl = static_cast<double>(t.left - prev->left) * m_per_tick;
      const double dr = static_cast<double>(t.right - prev->right) * m_per_tick;
      const double d = 0.5 * (dl + dr);
      const double dth = (dr - dl) / (2.0 * o.half_axle_m);
      pose.x += d * std::cos(pose.theta + 0.5 * dth);
      pose.y += d * std::sin(pose.theta + 0.5 * dth);
      pose.theta = std::remainder(pose.theta + dth, 2.0 * M_PI);
    }
    prev = t;
    pose.utime = utime;
    log.add_odometry(pose);
    log.add_scan(std::move(s));
  }
  record_end_of_input(reader, &log);
  return log;
}

}  // namespace rgnav::importers
