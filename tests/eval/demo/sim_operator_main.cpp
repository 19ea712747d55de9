// sim_operator: the demo's scripted operator. Answers the explorer's REGION_NAME_REQUEST with
// the simulated world's room name (REGION_NAME, as ./rgnav name-region does) and records the
// run for the demo's summary: the explorer's newest EXPLORER_STATUS, the names given, and the
// driven path and its length from SIM_TRUTH, written to --out (JSON, rewritten every second)
// and --path-out (CSV: t_s, world x, world y).
//   sim_operator [--world office] [--worlds-dir DIR] [--out FILE] [--path-out FILE] [--lcm-url URL]
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <cmath>
#include <fstream>
#include <optional>

#include "rgnav/explorer_status_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/region_name_request_t.hpp"
#include "rgnav/region_name_t.hpp"
#include "runtime/node.h"
#include "runtime/process_main.h"
#include "sim/world_yaml.h"
#include "sim_operator.h"
#include "time/message_time.h"

namespace {

const char* phase_name(int8_t p)
{
  switch (p) {
    case rgnav::explorer_status_t::PHASE_EXPLORING: return "exploring";
    case rgnav::explorer_status_t::PHASE_DONE: return "done";
    default: return "waiting";
  }
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"The demo's scripted operator: names the explorer's regions after the simulated world's rooms."};
  std::string world_name = "office", worlds_dir = rgnav::runtime::default_config_dir() + "/worlds", out, path_out, url;
  std::string request_channel = "REGION_NAME_REQUEST", name_channel = "REGION_NAME", status_channel = "EXPLORER_STATUS",
              truth_channel = "SIM_TRUTH";
  app.add_option("--world", world_name, "world name under --worlds-dir, or a file");
  app.add_option("--worlds-dir", worlds_dir, "folder of the worlds");
  app.add_option("--out", out, "JSON record of the run, rewritten every second");
  app.add_option("--path-out", path_out, "CSV of the driven path (t_s,x,y in the world frame)");
  app.add_option("--lcm-url", url, "LCM URL (default: LCM_DEFAULT_URL or LCM's default)");
  CLI11_PARSE(app, argc, argv);

  try {
    rgnav::demo::SimOperator op(rgnav::sim::load_world(rgnav::sim::resolve_world_path(world_name, worlds_dir)));
    rgnav::runtime::NodeOptions o;
    o.name = "sim_operator";
    o.lcm_url = url;
    o.input_stale_after = std::chrono::milliseconds(0);
    rgnav::runtime::Node node(o);

    std::optional<rgnav::explorer_status_t> status;
    double distance = 0, first_t = -1, last_t = 0;
    std::optional<Eigen::Vector2d> last_point;
    std::ofstream path;
    if (!path_out.empty()) {
      path.open(path_out);
      path << "t_s,x,y\n";
    }

    node.subscribe<rgnav::region_name_request_t>(request_channel, [&](const rgnav::region_name_request_t& m) {
      const auto a = op.name(m.region_id, m.centroid.x, m.centroid.y);
      rgnav::region_name_t n;
      n.utime = rgnav::time::wall_utime();
      n.region_id = m.region_id;
      n.name = a.name;
      node.publish(name_channel, n);
      spdlog::info("region {} ({}, world ({:.1f}, {:.1f})) is '{}'", m.region_id, m.description, a.world_x, a.world_y, a.name);
    });
    node.subscribe<rgnav::explorer_status_t>(status_channel, [&](const rgnav::explorer_status_t& m) {
      if (!status || status->phase != m.phase) spdlog::info("explorer: {} ({})", phase_name(m.phase), m.activity);
      status = m;
    });
    node.subscribe<rgnav::odometry_t>(truth_channel, [&](const rgnav::odometry_t& m) {
      const double t = static_cast<double>(m.utime) * 1e-6;
      if (first_t < 0) first_t = t;
      last_t = t;
      const Eigen::Vector2d p(m.odom_from_base.x, m.odom_from_base.y);
      if (last_point && (p - *last_point).norm() < 0.05) return;
      if (last_point) distance += (p - *last_point).norm();
      last_point = p;
      if (path.is_open()) path << (t - first_t) << "," << p.x() << "," << p.y() << "\n";
    });
    const auto write = [&] {
      if (out.empty()) return;
      nlohmann::json j;
      j["distance_m"] = distance;
      j["sim_time_s"] = first_t < 0 ? 0.0 : last_t - first_t;
      nlohmann::json names = nlohmann::json::array();
      for (const auto& [id, a] : op.answers()) names.push_back({{"region", id}, {"name", a.name}, {"room", a.room}, {"kind", a.kind}});
      j["names"] = names;
      if (status) {
        const auto& s = *status;
        j["explorer"] = {{"phase", phase_name(s.phase)}, {"activity", s.activity}, {"regions", s.regions},
                         {"complete_regions", s.complete_regions}, {"stack_pending", s.stack_pending},
                         {"stack_done", s.stack_done}, {"stack_set_aside", s.stack_set_aside}, {"goals_sent", s.goals_sent},
                         {"goals_reached", s.goals_reached}, {"goals_failed", s.goals_failed}};
      }
      const std::string tmp = out + ".tmp";
      std::ofstream(tmp) << j.dump(1) << "\n";
      std::rename(tmp.c_str(), out.c_str());
      if (path.is_open()) path.flush();
    };
    node.every(std::chrono::seconds(1), write);
    const int rc = node.run();
    write();
    return rc;
  } catch (const std::exception& e) {
    spdlog::error("sim_operator: {}", e.what());
    return 1;
  }
}
