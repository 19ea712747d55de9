// The three kinds of drive of the localization benchmark, in one world, on one localizer:
// tracking along the tour from the true start, global localization from random starts, and
// kidnaps. Each returns its world's JSON section and adds to the totals over all worlds. Every
// drive is also written for MRPT (carmen_drive.h).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "bench_world.h"
#include "localizer/localizer.h"
#include "sim_drive.h"

namespace rgnav::localize_eval {

// What the drives of one world share: the options, the random source (starts, simulator seeds)
// and the message time, which goes on from drive to drive.
struct TrialContext
{
  const sim::SimulatorOptions& sim;
  const localizer::LocalizerOptions& loc;
  std::mt19937_64& rng;
  int64_t utime = 0;
  int mrpt_scan_every = 3;

  // A drive along `route` starting now, heading to its second point.
  DriveSpec drive(const std::vector<sim::Vec2>& route, double max_s, const geometry::Pose2& odom_offset);
};

// Over all worlds, for the top-level keys.
struct Totals
{
  std::vector<double> track_xy, track_deg, global_time, global_travel, flag_time, recover_time, update_cpu_ms;
  std::vector<double> global_update_cpu_ms;   // every filter update of the global trials (unsure ones cost the searches)
  int64_t handovers = 0, divergences = 0, false_kidnaps = 0, gateway_events = 0;
  int64_t global_n = 0, global_ok = 0, global_estimate_ok = 0, global_wrong = 0, global_ambiguous = 0;
  std::map<std::string, int64_t> global_classes;   // trials per outcome (global_outcome.h)
  int64_t kidnap_n = 0, kidnap_ok = 0;
  int64_t particles_sum = 0, updates = 0;
  double cpu_s = 0, sim_s = 0;
};

nlohmann::json run_tracking(const BenchWorld& w, localizer::Localizer& loc, TrialContext& ctx, int laps, Totals& totals);
nlohmann::json run_global(const BenchWorld& w, localizer::Localizer& loc, TrialContext& ctx, int trials, int mrpt_trials,
                          Totals& totals);
nlohmann::json run_kidnaps(const BenchWorld& w, localizer::Localizer& loc, TrialContext& ctx, int trials, Totals& totals);

}  // namespace rgnav::localize_eval
