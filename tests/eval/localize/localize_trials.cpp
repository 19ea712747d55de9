#include "localize_trials.h"

#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "bench_stats.h"
#include "carmen_drive.h"
#include "global_outcome.h"

namespace rgnav::localize_eval {

using geometry::Pose2;

DriveSpec TrialContext::drive(const std::vector<sim::Vec2>& route, double max_s, const Pose2& odom_offset)
{
  DriveSpec d;
  d.route = route;
  d.start_heading = route.size() > 1 ? std::atan2(route[1].y() - route[0].y(), route[1].x() - route[0].x()) : 0.0;
  d.max_s = max_s;
  d.start_utime = utime;
  d.odom_offset = odom_offset;
  d.seed = rng();
  return d;
}

// The tour, `laps` times, from the pose the robot is put down at (given to the localizer).
nlohmann::json run_tracking(const BenchWorld& w, localizer::Localizer& loc, TrialContext& ctx, int laps, Totals& totals)
{
  std::vector<sim::Vec2> route;
  for (int lap = 0; lap < laps; ++lap) route.insert(route.end(), w.tour.begin() + (lap == 0 ? 0 : 1), w.tour.end());
  auto d = ctx.drive(route, 3600.0 * laps, Pose2());
  // LOCALIZE_SKIP_TRACKING=1: not driven (its random numbers drawn as in a full run), to study
  // a few global trials or kidnaps sooner.
  if (const char* skip = std::getenv("LOCALIZE_SKIP_TRACKING"); skip && std::string(skip) == "1") return nlohmann::json::object();
  CarmenDrive mrpt(w.dir + "/mrpt/track", ctx.loc.base_from_laser, ctx.mrpt_scan_every);
  const Pose2 start(route[0], d.start_heading);
  const int64_t r0 = w.frames.region_at(start);
  if (r0 == 0) throw std::runtime_error(w.name + ": the start lies in no region of the map");
  loc.set_pose(r0, w.frames.in_region(r0, start), ctx.loc.initial_xy, ctx.loc.initial_theta_deg * kDeg);
  mrpt.start("tracking", w.truth_in_grid(r0, start));
  const auto h0 = loc.stats().handovers;
  std::vector<double> exy, eth;
  std::ofstream trace;
  if (std::getenv("LOCALIZE_TRACE")) trace.open(w.dir + "/tracking_trace.txt");
  bool diverged = false;
  int64_t div = 0, updates = 0, particles = 0, events = 0;
  double cpu = 0;
  const auto res = run_drive(
      w.world, ctx.sim, d,
      [&](const DriveStep& s) {
        const double c0 = thread_cpu();
        const bool updated = loc.update(s.scan, s.odom_from_base);
        cpu += thread_cpu() - c0;
        if (loc.take_kidnap_flag()) ++totals.false_kidnaps;
        events += static_cast<int64_t>(loc.take_gateway_events().size());
        const int64_t rt = w.frames.region_at(s.world_from_base, loc.estimate().region);
        const Pose2 tg = rt ? w.truth_in_grid(rt, s.world_from_base) : Pose2();
        mrpt.scan(s.scan, s.odom_from_base, rt ? &tg : nullptr);
        if (!updated || !loc.estimate().valid) return;
        ++updates;
        particles += loc.stats().particles;
        const Error e = error_of(loc.estimate(), w.frames, s.world_from_base);
        if (trace) {
          const auto& est = loc.estimate();
          const Pose2 t = w.frames.in_region(est.region, s.world_from_base);
          trace << s.time_s << " r" << est.region << " truth_r" << rt << " est " << est.region_from_base.x() << " "
                << est.region_from_base.y() << " " << est.region_from_base.theta() << " true " << t.x() << " " << t.y() << " "
                << t.theta() << " err " << e.xy << " share " << est.cluster_share << " in " << est.inlier_ratio << " n "
                << loc.stats().particles << "\n";
        }
        exy.push_back(e.xy);
        eth.push_back(e.theta / kDeg);
        if (e.xy > kDivergedXy && !diverged) ++div;
        diverged = e.xy > kDivergedXy;
      },
      [&](const OdometryStep& o) { mrpt.odometry(o.utime, o.odom_from_base, o.v, o.omega); });
  ctx.utime = res.end_utime + 1'000'000;
  double se = 0, st = 0;
  for (size_t k = 0; k < exy.size(); ++k) {
    se += exy[k] * exy[k];
    st += eth[k] * eth[k];
  }
  const double n = std::max<double>(1, static_cast<double>(exy.size()));
  nlohmann::json t;
  t["seconds"] = res.seconds;
  t["distance_m"] = res.distance;
  t["updates"] = updates;
  t["rmse_m"] = std::sqrt(se / n);
  t["rmse_deg"] = std::sqrt(st / n);
  t["p95_m"] = number_or_null(percentile(exy, 0.95));
  t["p95_deg"] = number_or_null(percentile(eth, 0.95));
  t["max_m"] = exy.empty() ? 0.0 : *std::max_element(exy.begin(), exy.end());
  t["max_deg"] = eth.empty() ? 0.0 : *std::max_element(eth.begin(), eth.end());
  t["handovers"] = loc.stats().handovers - h0;
  t["gateway_passed_events"] = events;
  t["divergences"] = div;
  t["cpu_s"] = cpu;
  t["cpu_ms_per_update"] = updates ? 1e3 * cpu / static_cast<double>(updates) : 0.0;
  t["cpu_core_share"] = cpu / std::max(1e-9, res.seconds);
  t["particles_mean"] = updates ? static_cast<double>(particles) / static_cast<double>(updates) : 0.0;
  totals.track_xy.insert(totals.track_xy.end(), exy.begin(), exy.end());
  totals.track_deg.insert(totals.track_deg.end(), eth.begin(), eth.end());
  totals.handovers += loc.stats().handovers - h0;
  totals.divergences += div;
  totals.gateway_events += events;
  totals.cpu_s += cpu;
  totals.sim_s += res.seconds;
  totals.particles_sum += particles;
  totals.updates += updates;
  if (updates) totals.update_cpu_ms.push_back(1e3 * cpu / static_cast<double>(updates));
  return t;
}

namespace {

// Global localization counts when right (and staying so) from some time up to this on.
constexpr double kGlobalDeadlineS = 10.0;

// LOCALIZE_GLOBAL_TRIALS="world:trial ..." drives only those global trials, LOCALIZE_KIDNAP_TRIALS
// only those kidnaps ("none": none); the others still draw their random starts, so a trial
// starts where it does in a full run: to study a few.
bool trial_wanted(const char* variable, const std::string& world, int trial)
{
  const char* only = std::getenv(variable);
  if (!only || !*only) return true;
  return (" " + std::string(only) + " ").find(" " + world + ":" + std::to_string(trial) + " ") != std::string::npos;
}

std::string unsure_counts(const std::map<localizer::Unsure, int>& counts)
{
  std::string s;
  for (const auto& [why, n] : counts) s += std::string(" [") + localizer::to_string(why) + "] " + std::to_string(n);
  return s;
}

std::string claim_test_text(const localizer::ClaimTest& t)
{
  std::ostringstream o;
  o << "{lead " << t.lead << " margin " << t.margin << " all_beams " << t.lead_all_beams << " judged " << t.judged_beams << "/"
    << t.beams << " views " << t.views << " places " << t.places << " best_is_estimate " << t.best_is_estimate << " rival "
    << t.rival_distance << " m " << t.rival_turn_deg << " deg}";
  return o.str();
}

}  // namespace

// From random starts: 30 s drives along the tour from a random point, the pose unknown.
nlohmann::json run_global(const BenchWorld& w, localizer::Localizer& loc, TrialContext& ctx, int trials, int mrpt_trials,
                          Totals& totals)
{
  int ok = 0, estimate_ok = 0, wrong_claims = 0, ambiguous_n = 0;
  std::map<std::string, int> classes;
  int driven = 0;   // trials driven (all but when LOCALIZE_GLOBAL_TRIALS picks a few)
  std::vector<double> times, travels, update_cpu_ms;
  for (int trial = 0; trial < trials; ++trial) {
    const auto [k, s] = random_tour_point(w.tour, ctx.rng);
    const auto route = route_from(w.tour, k, s, 40.0);
    auto d = ctx.drive(route, 30.0, Pose2());
    if (!trial_wanted("LOCALIZE_GLOBAL_TRIALS", w.name, trial)) continue;
    ++driven;
    loc.start_global();
    std::unique_ptr<CarmenDrive> mrpt;
    if (trial < mrpt_trials) mrpt = std::make_unique<CarmenDrive>(w.dir + "/mrpt/global_" + std::to_string(trial), ctx.loc.base_from_laser, ctx.mrpt_scan_every);
    Settling settle, settle_estimate;
    Error last_error;
    bool started = false, wrong_claim = false;
    Pose2 truth_at_update;
    std::map<localizer::Unsure, int> unsure;   // updates per reason while unsure (trace)
    // At the deadline (global_outcome.h): unclaimed? the truth distinguishable? the estimate right?
    bool deadline_seen = false;
    GlobalTrialEnd end;
    // Unclaimed at the deadline (trace): the claim test of the estimate and the truth's lead.
    localizer::ClaimTest claim_test, truth_test;
    localizer::Unsure unsure_at_deadline = localizer::Unsure::kNone;
    const auto res = run_drive(
        w.world, ctx.sim, d,
        [&](const DriveStep& st) {
          const int64_t rt = w.frames.region_at(st.world_from_base, loc.estimate().region);
          if (mrpt) {
            const Pose2 tg = rt ? w.truth_in_grid(rt, st.world_from_base) : Pose2();
            if (!started && rt) mrpt->start("global", tg);
            started = started || rt;
            mrpt->scan(st.scan, st.odom_from_base, rt ? &tg : nullptr);
          }
          const double c0 = thread_cpu();
          const bool updated = loc.update(st.scan, st.odom_from_base);
          const double cpu_ms = 1e3 * (thread_cpu() - c0);
          if (!updated) return;
          update_cpu_ms.push_back(cpu_ms);
          if (loc.mode() == localizer::Mode::kGlobal) ++unsure[loc.unsure()];
          const Error e = error_of(loc.estimate(), w.frames, st.world_from_base);
          const bool claimed = loc.estimate().valid && loc.mode() == localizer::Mode::kTracking;
          settle.add(st.time_s, st.true_distance, claimed && e.good());
          settle_estimate.add(st.time_s, st.true_distance, loc.estimate().valid && e.good());
          wrong_claim = wrong_claim || (claimed && e.xy > kDivergedXy);
          if (!deadline_seen && st.time_s >= kGlobalDeadlineS) {
            deadline_seen = true;
            end.unclaimed_at_deadline = loc.mode() == localizer::Mode::kGlobal;
            end.estimate_good_at_deadline = loc.estimate().valid && e.good();
            if (end.unclaimed_at_deadline) {
              const int64_t r = w.frames.region_at(st.world_from_base, loc.estimate().region);
              end.truth_at_deadline = r ? loc.why_not_distinguishable(r, w.frames.in_region(r, st.world_from_base), &truth_test) : localizer::Unsure::kShortTravel;
              claim_test = loc.claim_test();
              unsure_at_deadline = loc.unsure();
            }
          }
          last_error = e;
          truth_at_update = st.world_from_base;
        },
        [&](const OdometryStep& o) {
          if (mrpt) mrpt->odometry(o.utime, o.odom_from_base, o.v, o.omega);
        });
    ctx.utime = res.end_utime + 1'000'000;
    const bool success = settle.good_now && settle.first_good_after <= kGlobalDeadlineS;
    ok += success;
    estimate_ok += settle_estimate.good_now && settle_estimate.first_good_after <= kGlobalDeadlineS;
    wrong_claims += wrong_claim;
    // Still unsure at the end, and rightly so: some place >= unique_distance from the true pose
    // explains the views of the robot's last metres as well as the true pose does.
    bool ambiguous = false;
    if (!success && loc.mode() == localizer::Mode::kGlobal) {
      const int64_t rt = w.frames.region_at(truth_at_update, loc.estimate().region);
      ambiguous = rt != 0 && !loc.distinguishable(rt, w.frames.in_region(rt, truth_at_update));
    }
    ambiguous_n += ambiguous;
    end.success = success;
    end.wrong_claim = wrong_claim;
    const char* why = outcome_class(end);
    ++classes[why];
    if (std::getenv("LOCALIZE_TRACE"))
      std::cerr << w.name << " global " << trial << (success ? " ok" : ambiguous ? " AMBIGUOUS" : " FAIL") << " settled " << settle.first_good_after
                << " estimate_settled " << settle_estimate.first_good_after << " wrong_claim " << wrong_claim
                << " error " << last_error.xy << " m " << last_error.theta / kDeg << " deg mode " << localizer::to_string(loc.mode())
                << " share " << loc.estimate().cluster_share << " inliers " << loc.estimate().inlier_ratio << " region "
                << loc.estimate().region << " fit " << (w.frames.fit_rmse.count(loc.estimate().region) ? w.frames.fit_rmse.at(loc.estimate().region) : NAN) << " start " << route[0].x()
                << " " << route[0].y() << " unsure" << unsure_counts(unsure) << " class " << why << " truth_at_deadline "
                << localizer::to_string(end.truth_at_deadline);
    if (std::getenv("LOCALIZE_TRACE") && end.unclaimed_at_deadline)
      std::cerr << " deadline [" << localizer::to_string(unsure_at_deadline) << "] claim_test " << claim_test_text(claim_test)
                << " truth_test " << claim_test_text(truth_test);
    if (std::getenv("LOCALIZE_TRACE")) std::cerr << "\n";
    if (settle.good_now) {
      times.push_back(settle.first_good_after);
      travels.push_back(settle.distance_at);
    }
  }
  nlohmann::json g;
  g["trials"] = driven;
  g["success_ratio"] = driven ? static_cast<double>(ok) / driven : 0.0;
  g["estimate_success_ratio"] = driven ? static_cast<double>(estimate_ok) / driven : 0.0;
  g["wrong_claims"] = wrong_claims;
  g["ambiguous"] = ambiguous_n;
  g["classes"] = classes;
  for (const auto& [why, n] : classes) totals.global_classes[why] += n;
  g["time_s_p50"] = number_or_null(percentile(times, 0.5));
  // CPU of the filter updates in these drives (the searches of global localization included).
  g["cpu_ms_per_update_p50"] = number_or_null(percentile(update_cpu_ms, 0.5));
  g["cpu_ms_per_update_p99"] = number_or_null(percentile(update_cpu_ms, 0.99));
  g["cpu_ms_per_update_max"] = number_or_null(update_cpu_ms.empty() ? NAN : *std::max_element(update_cpu_ms.begin(), update_cpu_ms.end()));
  totals.global_update_cpu_ms.insert(totals.global_update_cpu_ms.end(), update_cpu_ms.begin(), update_cpu_ms.end());
  g["travel_m_p50"] = number_or_null(percentile(travels, 0.5));
  totals.global_ok += ok;
  totals.global_estimate_ok += estimate_ok;
  totals.global_wrong += wrong_claims;
  totals.global_ambiguous += ambiguous_n;
  totals.global_n += driven;
  totals.global_time.insert(totals.global_time.end(), times.begin(), times.end());
  totals.global_travel.insert(totals.global_travel.end(), travels.begin(), travels.end());
  return g;


}

// 10 s of tracking, then the robot is carried to another random place (its odometry goes on
// where it was) and driven on for 40 s.
nlohmann::json run_kidnaps(const BenchWorld& w, localizer::Localizer& loc, TrialContext& ctx, int trials, Totals& totals)
{
  int ok = 0, flagged = 0;
  int driven = 0;   // kidnaps driven (all but when LOCALIZE_KIDNAP_TRIALS picks a few)
  std::vector<double> flags, recovers;
  for (int trial = 0; trial < trials; ++trial) {
    const auto [k, s] = random_tour_point(w.tour, ctx.rng);
    const auto route = route_from(w.tour, k, s, 20.0);
    auto d = ctx.drive(route, 10.0, Pose2());
    const Pose2 start(route[0], d.start_heading);
    const int64_t r0 = w.frames.region_at(start);
    if (r0 == 0 || !loc.set_pose(r0, w.frames.in_region(r0, start), ctx.loc.initial_xy, ctx.loc.initial_theta_deg * kDeg)) {
      --trial;
      continue;
    }
    // Somewhere at least 5 m away.
    std::vector<sim::Vec2> route_b;
    for (int attempt = 0; attempt < 50; ++attempt) {
      const auto [kb, sb] = random_tour_point(w.tour, ctx.rng);
      route_b = route_from(w.tour, kb, sb, 40.0);
      if ((route_b[0] - route.back()).norm() >= 5.0) break;
    }
    if (!trial_wanted("LOCALIZE_KIDNAP_TRIALS", w.name, trial)) {
      ctx.drive(route_b, 40.0, Pose2());   // its random numbers drawn as in a full run
      continue;
    }
    ++driven;
    const auto a = run_drive(w.world, ctx.sim, d, [&](const DriveStep& st) { loc.update(st.scan, st.odom_from_base); });
    loc.take_kidnap_flag();
    ctx.utime = a.end_utime + 100'000;
    auto db = ctx.drive(route_b, 40.0, a.end_odom);
    Settling settle;
    double flag_s = NAN;
    std::map<localizer::Unsure, int> unsure;   // updates per reason while unsure (trace)
    const auto b = run_drive(w.world, ctx.sim, db, [&](const DriveStep& st) {
      const bool updated = loc.update(st.scan, st.odom_from_base);
      if (loc.take_kidnap_flag() && std::isnan(flag_s)) flag_s = st.time_s;
      if (!updated) return;
      if (loc.mode() == localizer::Mode::kGlobal) ++unsure[loc.unsure()];
      const bool good = loc.estimate().valid && loc.mode() == localizer::Mode::kTracking &&
                        error_of(loc.estimate(), w.frames, st.world_from_base).good();
      settle.add(st.time_s, st.true_distance, good);
    });
    ctx.utime = b.end_utime + 1'000'000;
    if (!std::isnan(flag_s)) {
      ++flagged;
      flags.push_back(flag_s);
    }
    const bool recovered = settle.good_now && settle.first_good_after <= 30.0;
    ok += recovered;
    if (std::getenv("LOCALIZE_TRACE"))
      std::cerr << w.name << " kidnap " << trial << (recovered ? " ok" : " FAIL") << " flagged " << flag_s << " settled "
                << settle.first_good_after << " mode " << localizer::to_string(loc.mode()) << " share "
                << loc.estimate().cluster_share << " carried " << (route_b[0] - route.back()).norm() << " m unsure" << unsure_counts(unsure) << "\n";
    if (settle.good_now) recovers.push_back(settle.first_good_after);
  }
  nlohmann::json kj;
  kj["trials"] = driven;
  kj["flagged"] = flagged;
  kj["flag_s_p50"] = number_or_null(percentile(flags, 0.5));
  kj["recovered_ratio"] = driven ? static_cast<double>(ok) / driven : 0.0;
  kj["recover_s_p50"] = number_or_null(percentile(recovers, 0.5));
  totals.kidnap_ok += ok;
  totals.kidnap_n += driven;
  totals.flag_time.insert(totals.flag_time.end(), flags.begin(), flags.end());
  totals.recover_time.insert(totals.recover_time.end(), recovers.begin(), recovers.end());
  return kj;

}

}  // namespace rgnav::localize_eval
