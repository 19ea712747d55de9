// Replays one drive of the localization benchmark (the CARMEN log it writes for MRPT, every
// `--mrpt-scan-every`-th scan, with the true pose in the occupancy grid's frame) on the bench's
// map, and prints per filter update what the localizer decided and why: its mode, the reason it
// stayed unsure and the numbers of its claim test (Localizer::claim_test), the estimate's error.
// To study why a global trial was or was not claimed without driving the whole benchmark:
//   rgnav_localize_replay --map logs/bench/localize/office/rgmap.json
//     --drive logs/bench/localize/office/mrpt/global_4 [--localizer-config FILE]
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include "config/finish_except.h"
#include "config/robot_description.h"
#include "localizer/localizer.h"
#include "localizer/localizer_options.h"
#include "render/rgmap_picture.h"
#include "rgmap/saved_map.h"
#include "runtime/process_main.h"

namespace lo = rgnav::localizer;
using rgnav::geometry::normalize_angle;
using rgnav::geometry::Pose2;

namespace {

constexpr double kLaserRangeMax = 8.183;   // [m] the simulated LMS 2xx in its 8 m mode (config/sim.yaml)

struct Truth
{
  double t = 0;
  Pose2 grid_from_base;
};

std::vector<Truth> read_truth(const std::string& path)
{
  std::vector<Truth> out;
  std::ifstream f(path);
  double t = 0, x = 0, y = 0, th = 0;
  while (f >> t >> x >> y >> th) out.push_back({t, Pose2(x, y, th)});
  return out;
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Replays a localization-benchmark drive and prints the localizer's claim decisions"};
  const std::string cfg_dir = rgnav::runtime::default_config_dir();
  std::string map_path, drive_dir, localizer_config = cfg_dir + "/localizer.yaml", robot_path = cfg_dir + "/robot.yaml";
  app.add_option("--map", map_path, "the bench's rgmap.json")->required()->check(CLI::ExistingFile);
  app.add_option("--drive", drive_dir, "a drive folder (drive.carmen, truth.txt)")->required()->check(CLI::ExistingDirectory);
  app.add_option("--localizer-config", localizer_config, "localizer config")->check(CLI::ExistingFile);
  app.add_option("--robot", robot_path, "robot description")->check(CLI::ExistingFile);
  bool truth_test = false;
  app.add_flag("--truth-test", truth_test, "also the true pose's lead as the claim test counts it (a path search per update: slow)");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::warn);
  try {
    const auto robot = rgnav::config::load_robot_description_file(robot_path);
    const auto cfg = rgnav::config::Config::load(localizer_config);
    const auto options = lo::load_localizer_options(cfg, robot).localizer;
    rgnav::config::finish_except(cfg, {"node"});
    const auto map = rgnav::rgmap::load_saved_map(map_path);
    const auto grid_from_region = rgnav::render::compose_region_frames(map);
    const auto truth = read_truth(drive_dir + "/truth.txt");
    lo::Localizer loc(options);
    loc.set_map(map);
    std::ifstream log(drive_dir + "/drive.carmen");
    std::string line;
    int64_t scan_id = 0;
    size_t ti = 0;
    double t0 = NAN;
    while (std::getline(log, line)) {
      std::istringstream in(line);
      std::string kind;
      int n = 0;
      in >> kind;
      if (kind != "FLASER" || !(in >> n)) continue;
      rgnav::sensors::LaserScan scan;
      scan.angle_min = -M_PI / 2;
      scan.angle_increment = M_PI / std::max(1, n - 1);
      scan.range_max = kLaserRangeMax;
      scan.ranges.resize(static_cast<size_t>(n));
      for (auto& r : scan.ranges) in >> r;
      double lx = 0, ly = 0, lth = 0, ox = 0, oy = 0, oth = 0, t = 0;
      in >> lx >> ly >> lth >> ox >> oy >> oth >> t;
      if (std::isnan(t0)) t0 = t;
      scan.utime = static_cast<int64_t>(std::llround(t * 1e6));
      scan.scan_id = ++scan_id;
      if (!loc.update(scan, Pose2(ox, oy, oth))) continue;
      while (ti + 1 < truth.size() && truth[ti + 1].t <= t + 1e-4) ++ti;
      const auto& e = loc.estimate();
      std::cout << std::fixed;
      std::cout.precision(2);
      std::cout << t - t0 << " " << lo::to_string(loc.mode());
      if (e.valid && !truth.empty() && grid_from_region.count(e.region)) {
        const Pose2 est = grid_from_region.at(e.region) * e.region_from_base;
        const Pose2& tr = truth[ti].grid_from_base;
        std::cout << " err " << (est.translation() - tr.translation()).norm() << " m "
                  << normalize_angle(est.theta() - tr.theta()) * 180 / M_PI << " deg";
      }
      if (loc.mode() == lo::Mode::kGlobal) {
        const auto& c = loc.claim_test();
        std::cout << " [" << lo::to_string(loc.unsure()) << "] lead " << c.lead << " margin " << c.margin << " all_beams "
                  << c.lead_all_beams << " judged " << c.judged_beams << "/" << c.beams << " views " << c.views << " places "
                  << c.places << " rival " << c.rival_distance << " m " << c.rival_turn_deg << " deg";
        if (truth_test && !truth.empty()) {
          // The true pose in the region whose freespace holds it (the grid places every region).
          for (const auto& [id, grid_from] : grid_from_region) {
            const lo::RegionModel* m = loc.maps().region(id);
            const Pose2 p = grid_from.inverse() * truth[ti].grid_from_base;
            if (!m || !m->is_free(p.translation()) || !m->in_bbox(p.translation(), 0.0)) continue;
            lo::ClaimTest tt;
            const auto why = loc.why_not_distinguishable(id, p, &tt);
            std::cout << " | truth [" << lo::to_string(why) << "] lead " << tt.lead << " margin " << tt.margin << " all_beams "
                      << tt.lead_all_beams << " judged " << tt.judged_beams << "/" << tt.beams << " rival " << tt.rival_distance
                      << " m " << tt.rival_turn_deg << " deg";
            break;
          }
        }
      }
      std::cout << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "localize replay: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
