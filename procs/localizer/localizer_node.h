// Node adapter of the localizer: RG_MAP (or a saved map loaded at start), ODOMETRY,
// LASER_FRONT and LOCALIZE_REQUEST in; POSE (per filter update) and LOCALIZER_GATEWAY_PASSED
// out. Odometry is kept for a few seconds and interpolated at each scan's time; a scan that
// has no odometry on both sides of it within max_scan_age is dropped and counted (it waits
// for the odometry after it, never for longer than that). The estimate is saved to the state
// file every persist_period of message time while the filter is converged, and a restarted
// localizer resumes tracking near it. The mode, particle count, confidence and kidnaps go into
// the heartbeat status (DEGRADED while not tracking, or when no scan was used for a second).
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <utility>

#include "geometry/pose2.h"
#include "localizer/localizer.h"
#include "localizer/localizer_options.h"
#include "localizer/saved_estimate.h"
#include "rgmap/rg_map.h"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/localize_request_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/rg_map_t.hpp"
#include "runtime/node.h"
#include "sensors/laser_scan.h"

namespace rgnav::localizer {

// What the localizer reads and writes besides the bus (its command-line flags).
struct LocalizerFiles
{
  std::string map;          // --map: an rgmap.json (checkpoint framing) or a folder holding one; "" = wait for RG_MAP
  std::string state_file;   // --state-file: the estimate saved while converged, resumed at start; "" = none
};

class LocalizerNode
{
 public:
  // Throws config::ConfigError when files.map cannot be loaded (the process refuses to start).
  LocalizerNode(runtime::Node& node, const LocalizerNodeOptions& options, LocalizerFiles files = {});
  ~LocalizerNode();
  LocalizerNode(const LocalizerNode&) = delete;
  LocalizerNode& operator=(const LocalizerNode&) = delete;

  const Localizer& localizer() const { return loc_; }
  // The saved estimate this instance resumed from (set once a map was there to resume in).
  const std::optional<SavedEstimate>& resumed_from() const { return resumed_from_; }
  int64_t estimates_saved() const { return saves_; }

 private:
  struct OdometrySample
  {
    int64_t utime;
    geometry::Pose2 odom_from_base;
  };

  void on_map(const rg_map_t& m);
  void take_map(const rgmap::RgMap& map, const std::string& source);
  void on_odometry(const odometry_t& m);
  void accept_odometry(int64_t seq, const OdometrySample& sample);
  void on_scan(const laser_scan_t& m);
  void on_request(const localize_request_t& m);
  // The odometry pose at utime between the samples around it, each within max_scan_age.
  std::optional<geometry::Pose2> odometry_at(int64_t utime) const;
  void process(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_base);
  void drop_scan(const sensors::LaserScan& scan, const std::string& why);
  void odometry_restarted(const std::string& why);
  void publish_estimate();
  // Saves a converged estimate when persist_period of scan time has passed (or `now`).
  void save(bool now);
  void report();

  runtime::Node& node_;
  const LocalizerNodeOptions options_;
  const LocalizerFiles files_;
  Localizer loc_;
  const int64_t max_scan_age_us_;
  const int64_t max_odometry_gap_us_;        // a longer step in odometry time waits for confirmation
  const int64_t persist_period_us_;
  std::deque<OdometrySample> odometry_;
  int64_t last_odometry_seq_ = -1;
  struct HeldOdometry
  {
    int64_t seq;
    OdometrySample sample;
    bool restart;                            // its sequence went back (else its time jumped ahead)
  };
  std::optional<HeldOdometry> held_;         // waiting for the next sample to continue from it
  std::deque<sensors::LaserScan> pending_;   // newer than the newest odometry: waiting for the sample after them
  int64_t last_scan_utime_ = 0;
  std::chrono::steady_clock::time_point last_scan_used_{};   // wall time, for the status only
  std::optional<SavedEstimate> saved_;       // loaded at start, resumed when a map is there
  std::optional<SavedEstimate> resumed_from_;
  int64_t saves_ = 0;
  int64_t last_saved_utime_ = 0;
  bool save_failed_ = false;
  Mode reported_mode_ = Mode::kNoMap;
  std::string reported_text_;
};

}  // namespace rgnav::localizer
