#include "offline_mapping.h"

#include <lcm/lcm-cpp.hpp>
#include <opencv2/imgcodecs.hpp>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "bus/typed.h"
#include "scan_mapper/scan_mapper_conversions.h"

namespace rgnav::scan_mapper {
namespace {

double thread_cpu_seconds()
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

Scan to_scan(const importers::ScanRecord& r, int64_t id)
{
  Scan s;
  s.utime = r.utime;
  s.scan_id = r.scan_id > 0 ? r.scan_id : id;
  s.angle_min = r.angle_min;
  s.angle_increment = r.angle_increment;
  s.range_min = r.range_min;
  s.range_max = r.range_max;
  s.ranges = r.ranges;
  return s;
}

}  // namespace

OfflineResult run_offline(const importers::ImportedLog& log, const ScanMapperOptions& options)
{
  OfflineResult res;
  ScanMapper mapper(options);
  OdometryBuffer odom;
  std::vector<ScanEstimate> raw;  // scan, odometry (map pose filled in after the run)
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = thread_cpu_seconds();
  int64_t next_id = 0;
  for (const auto& e : log.events) {
    if (e.kind == importers::LogEvent::Kind::kOdometry) {
      const auto& p = log.odometry[e.index];
      const OdometrySample s{p.utime, Pose2{p.x, p.y, normalize_angle(p.theta)}};
      mapper.add_odometry(s);
      odom.add(s);
    } else if (e.kind == importers::LogEvent::Kind::kScan) {
      const Scan scan = to_scan(log.scans[e.index], ++next_id);
      mapper.add_scan(scan);
      if (const auto o = odom.at(scan.utime, options.max_odometry_extrapolation_us))
        raw.push_back({scan.scan_id, scan.utime, *o, {}});
    }
  }
  res.cpu_seconds = thread_cpu_seconds() - cpu0;
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  res.nodes = mapper.nodes();
  res.stats = mapper.stats();
  if (!log.scans.empty()) res.log_seconds = 1e-6 * static_cast<double>(log.scans.back().utime - log.scans.front().utime);
  // Scans between accepted ones: the last accepted scan's final estimate plus odometry.
  size_t k = 0;
  for (auto& s : raw) {
    while (k + 1 < res.nodes.size() && res.nodes[k + 1].scan.scan_id <= s.scan_id) ++k;
    if (res.nodes.empty() || res.nodes[k].scan.scan_id > s.scan_id) continue;
    const auto& n = res.nodes[k];
    s.map_from_base = n.map_from_base * between(n.odom_from_base, s.odom_from_base);
    res.scans.push_back(s);
  }
  return res;
}

double write_outputs(const OfflineResult& r, const ScanMapperOptions& options, const std::string& dir)
{
  std::filesystem::create_directories(dir);
  {
    std::ofstream t(dir + "/trajectory.txt");
    t << "# scan_id utime_us x_m y_m theta_rad odom_x_m odom_y_m odom_theta_rad (accepted scans, final estimate)\n";
    t.precision(9);
    for (const auto& n : r.nodes)
      t << n.scan.scan_id << ' ' << n.scan.utime << ' ' << n.map_from_base.x << ' ' << n.map_from_base.y << ' '
        << n.map_from_base.theta << ' ' << n.odom_from_base.x << ' ' << n.odom_from_base.y << ' '
        << n.odom_from_base.theta << '\n';
    if (!t) throw std::runtime_error("cannot write " + dir + "/trajectory.txt");
  }
  {
    lcm::LogFile f(dir + "/aligned_scans.lcmlog", "w");
    if (!f.good()) throw std::runtime_error("cannot write " + dir + "/aligned_scans.lcmlog");
    int64_t num = 0;
    for (const auto& n : r.nodes) {
      const auto m = to_aligned_scan(n, options.base_from_laser, "laser_front");
      std::vector<uint8_t> buf;
      std::string why;
      if (!bus::encode(m, &buf, &why)) throw std::runtime_error("invalid aligned scan: " + why);
      lcm::LogEvent ev;
      ev.eventnum = num++;
      ev.timestamp = m.utime;
      ev.channel = "ALIGNED_SCAN";
      ev.datalen = static_cast<int32_t>(buf.size());
      ev.data = buf.data();
      f.writeEvent(&ev);
    }
  }
  OccupancyOptions oo;
  oo.max_range_m = options.points.max_range_m;
  const auto grid = OccupancyGrid::build(r.nodes, options.base_from_laser, oo);
  if (!cv::imwrite(dir + "/map.png", grid.render())) throw std::runtime_error("cannot write " + dir + "/map.png");
  return grid.consistency(r.nodes, options.base_from_laser, 0.05);
}

}  // namespace rgnav::scan_mapper
