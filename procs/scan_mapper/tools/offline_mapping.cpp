#include "offline_mapping.h"

#include <lcm/lcm-cpp.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "bus/typed.h"
#include "scan_mapper/scan_mapper_conversions.h"

namespace rgnav::scan_mapper {

double thread_cpu_seconds()
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

namespace {

// A log scan with its id: the log's, or `id` for logs without ids.
sensors::LaserScan with_id(sensors::LaserScan s, int64_t id)
{
  if (s.scan_id <= 0) s.scan_id = id;
  return s;
}

// The pose of a scan that was not accepted, between nodes[k] and nodes[k + 1] (see below).
Pose2 register_between(const std::vector<ScanNode>& nodes, size_t k, const ScanEstimate& s, const sensors::LaserScan& scan,
                       const ScanMapperOptions& options)
{
  const Pose2 by_odometry = s.map_from_base;
  if (k + 1 >= nodes.size()) return by_odometry;
  const ScanNode& a = nodes[k];
  const ScanNode& b = nodes[k + 1];
  const double span = static_cast<double>(b.scan.utime - a.scan.utime);
  const double f = span > 0 ? std::clamp(static_cast<double>(s.utime - a.scan.utime) / span, 0.0, 1.0) : 0.0;
  const Pose2 by_time = interpolate(a.map_from_base, b.map_from_base, f);
  Points model, normals;
  std::vector<char> has_normal;
  const size_t lo = k >= 2 ? k - 2 : 0, hi = std::min(nodes.size() - 1, k + 3);
  for (size_t i = lo; i <= hi; ++i) {
    const auto& ni = nodes[i];
    const auto pts = transform_points(ni.map_from_base, ni.points);
    model.insert(model.end(), pts.begin(), pts.end());
    for (const auto& v : transform_points(Pose2(0, 0, ni.map_from_base.theta()), ni.normals)) normals.push_back(v);
    has_normal.insert(has_normal.end(), ni.has_normal.begin(), ni.has_normal.end());
  }
  const Points points = scan_to_points(scan, options.base_from_laser, options.points);
  if (model.size() < 10 || points.size() < 10) return by_odometry;
  const PointMap map(std::move(model), std::move(normals), std::move(has_normal));
  // The scan's own normals, as the nodes' (ScanMapper).
  const ScanNormals own = scan_normals(points, options.base_from_laser.translation(), options.normals);
  IcpResult best;
  for (const Pose2& guess : {by_odometry, by_time}) {
    const IcpResult r = icp_point_to_line(points, own.normals, own.has_normal, map, guess, options.icp);
    if (r.ok && (!best.ok || r.inlier_ratio > best.inlier_ratio)) best = r;
  }
  if (!best.ok || best.inlier_ratio < options.min_inlier_ratio) {
    // Far off (a fast turn): the same correlative search as the mapper's retry, then ICP.
    const LikelihoodGrid grid(map.points(), options.correlative);
    const auto cor = correlative_match(thin_points(points, options.loop.point_spacing_m), grid, by_time,
                                       options.local_window, options.correlative);
    const IcpResult r = icp_point_to_line(points, own.normals, own.has_normal, map, cor.map_from_scan, options.icp);
    if (r.ok && (!best.ok || r.inlier_ratio > best.inlier_ratio)) best = r;
  }
  return best.ok && best.inlier_ratio >= options.loop.min_inlier_ratio ? best.map_from_scan : by_odometry;
}

}  // namespace

OfflineResult run_offline(const importers::ImportedLog& log, const ScanMapperOptions& options)
{
  OfflineResult res;
  ScanMapper mapper(options);
  OdometryBuffer odom;
  std::vector<ScanEstimate> raw;  // scan, odometry (map pose filled in after the run)
  std::vector<sensors::LaserScan> scans;        // ... and the scan itself
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
      const sensors::LaserScan scan = with_id(log.scans[e.index], ++next_id);
      mapper.add_scan(scan);
      if (const auto o = odom.at(scan.utime, options.max_odometry_extrapolation_us)) {
        raw.push_back({scan.scan_id, scan.utime, *o, {}});
        scans.push_back(scan);
      }
    }
  }
  res.nodes = mapper.nodes();
  res.stats = mapper.stats();
  if (!log.scans.empty()) res.log_seconds = 1e-6 * static_cast<double>(log.scans.back().utime - log.scans.front().utime);
  // Scans between accepted ones: registered against their accepted neighbours' final
  // estimates, from two guesses: the previous accepted scan carried forward by odometry, and
  // the pose interpolated in time between the accepted scans around it (better where
  // odometry and scans are out of step, e.g. turning in place), and if neither fits well, a
  // correlative search around the latter. Nothing fitting: odometry.
  size_t k = 0;
  for (auto& s : raw) {
    while (k + 1 < res.nodes.size() && res.nodes[k + 1].scan.scan_id <= s.scan_id) ++k;
    if (res.nodes.empty() || res.nodes[k].scan.scan_id > s.scan_id) continue;
    const auto& n = res.nodes[k];
    s.map_from_base = n.map_from_base * between(n.odom_from_base, s.odom_from_base);
    if (n.scan.scan_id != s.scan_id) s.map_from_base = register_between(res.nodes, k, s, scans[&s - raw.data()], options);
    res.scans.push_back(s);
  }
  res.cpu_seconds = thread_cpu_seconds() - cpu0;
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
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
      t << n.scan.scan_id << ' ' << n.scan.utime << ' ' << n.map_from_base.x() << ' ' << n.map_from_base.y() << ' '
        << n.map_from_base.theta() << ' ' << n.odom_from_base.x() << ' ' << n.odom_from_base.y() << ' '
        << n.odom_from_base.theta() << '\n';
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

void write_truth_pairs(const std::string& path, const std::vector<ScanNode>& nodes, const std::vector<Pose2>& truth,
                       const std::vector<Pose2>* online, const std::vector<int>* loop_closed_at)
{
  std::ofstream out(path);
  out << "# scan_id utime_us true_x true_y true_theta est_x est_y est_theta"
      << (online ? " online_x online_y online_theta loop_closed" : "") << "\n";
  const auto put = [&out](const Pose2& p) { out << ' ' << p.x() << ' ' << p.y() << ' ' << p.theta(); };
  for (size_t k = 0; k < nodes.size() && k < truth.size() && (!online || k < online->size()); ++k) {
    out << nodes[k].scan.scan_id << ' ' << nodes[k].scan.utime;
    put(truth[k]);
    put(nodes[k].map_from_base);
    if (online) {
      put((*online)[k]);
      const bool closed = loop_closed_at && std::binary_search(loop_closed_at->begin(), loop_closed_at->end(), static_cast<int>(k));
      out << ' ' << closed;
    }
    out << '\n';
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace rgnav::scan_mapper
