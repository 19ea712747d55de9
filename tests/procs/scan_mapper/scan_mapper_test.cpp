// The mapping library end to end on a synthetic run: drifting odometry, scans of a known
// world; plus odometry interpolation, options validation and state persistence.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "config/config.h"
#include "scan_mapper/mapper_state_io.h"
#include "scan_mapper/odometry_buffer.h"
#include "scan_mapper/relations_metric.h"
#include "scan_mapper/scan_mapper.h"
#include "synthetic_world.h"

namespace sm = rgnav::scan_mapper;
namespace fs = std::filesystem;

namespace {

struct SyntheticRun
{
  std::vector<sm::Pose2> truth;   // per scan
  std::vector<sm::Pose2> odom;    // drifting odometry per scan
  std::vector<rgnav::sensors::LaserScan> scans;
};

// Drives along the waypoints (from the first) `laps` times with biased odometry (2 % scale,
// 1 deg/m) and, given odom_step_sigma, a random error of each 5 cm step's length (relative).
SyntheticRun make_run(const std::vector<sm::testing::Segment>& world, const std::vector<Eigen::Vector2d>& waypoints,
                      int laps, const sm::testing::LaserModel& m, double odom_step_sigma = 0.0)
{
  SyntheticRun r;
  std::mt19937 rng(1);
  std::mt19937 odom_rng(2);
  std::normal_distribution<double> step_error(0.0, odom_step_sigma > 0.0 ? odom_step_sigma : 1.0);
  sm::Pose2 truth{waypoints[0].x(), waypoints[0].y(), 0}, odom = truth;
  int64_t t = 1'000'000, id = 0;
  for (int lap = 0; lap < laps; ++lap)
    for (size_t w = 1; w < waypoints.size(); ++w) {
      const Eigen::Vector2d goal = waypoints[w];
      for (int guard = 0; guard < 500; ++guard) {
        const Eigen::Vector2d d = goal - Eigen::Vector2d(truth.x(), truth.y());
        if (d.norm() < 0.05) break;
        const double heading = std::atan2(d.y(), d.x());
        const double turn = sm::normalize_angle(heading - truth.theta());
        const sm::Pose2 step = std::fabs(turn) > 0.05 ? sm::Pose2{0, 0, std::clamp(turn, -0.1, 0.1)}
                                                      : sm::Pose2{std::min(0.05, d.norm()), 0, turn};
        truth = truth * step;
        // Odometry: scale and heading bias.
        const double length_error = odom_step_sigma > 0.0 ? step_error(odom_rng) : 0.0;
        odom = odom * sm::Pose2{step.x() * (1.02 + length_error), 0, step.theta() * 1.01 + step.x() * (M_PI / 180)};
        t += 50'000;
        r.truth.push_back(truth);
        r.odom.push_back(odom);
        r.scans.push_back(sm::testing::cast_scan(world, truth, m, &rng, ++id, t));
      }
    }
  return r;
}

// A loop through the synthetic office, twice.
SyntheticRun make_run()
{
  sm::testing::LaserModel m;
  m.noise_m = 0.01;
  return make_run(sm::testing::office_world(), {{1, 0}, {10, 0}, {10, 4}, {1, 4.5}, {1, 0}}, 2, m);
}

sm::ScanMapperOptions test_options()
{
  sm::ScanMapperOptions o;
  o.base_from_laser = sm::Pose2{};
  return o;
}

// test_options with the shipped config's hallway rule: a translation direction held by fewer
// than 60 surface points is left to odometry (1 m^2 on the match).
sm::ScanMapperOptions hallway_options()
{
  auto o = test_options();
  o.icp.degenerate_min_points = 60.0;
  o.icp.degenerate_variance_m2 = 1.0;
  return o;
}

// A 2 m wide hallway with a few door niches, 42 m long, driven from its end 24 m out and back
// `laps` times (a 6 m laser: most scans see the walls and a jamb or two).
SyntheticRun hallway_out_and_back(int laps)
{
  std::vector<sm::testing::Segment> world = {{{-2, -1}, {40, -1}}, {{-2, 1}, {40, 1}}, {{-2, -1}, {-2, 1}},
                                             {{40, -1}, {40, 1}}};
  for (const double x : {4.0, 11.0, 19.5, 26.0, 34.0}) {
    const double side = x < 15.0 || x > 30.0 ? 1.0 : -1.0;
    world.push_back({{x, side}, {x, side * 1.4}});
    world.push_back({{x + 1.0, side}, {x + 1.0, side * 1.4}});
    world.push_back({{x, side * 1.4}, {x + 1.0, side * 1.4}});
  }
  sm::testing::LaserModel m;
  m.noise_m = 0.01;
  m.max_range = 6.0;
  return make_run(world, {{0, 0}, {24, 0}, {0, 0}}, laps, m);
}

// Every scan of the run with its odometry, in order.
void feed(const SyntheticRun& run, sm::ScanMapper* mapper)
{
  for (size_t i = 0; i < run.scans.size(); ++i) {
    mapper->add_odometry({run.scans[i].utime, run.odom[i]});
    mapper->add_scan(run.scans[i]);
  }
}

// A furnished 7 x 6 m room (a cupboard and a table) and, through its east wall, a plain 2 m
// hallway 40 m long.
std::vector<sm::testing::Segment> furnished_room_and_hallway()
{
  std::vector<sm::testing::Segment> world = {{{-7, -3}, {0, -3}}, {{-7, 3}, {0, 3}}, {{-7, -3}, {-7, 3}},
                                             {{0, -3}, {0, -1}},  {{0, 1}, {0, 3}},   {{0, -1}, {40, -1}},
                                             {{0, 1}, {40, 1}},   {{40, -1}, {40, 1}}};
  auto box = [&](double x0, double y0, double x1, double y1) {
    world.push_back({{x0, y0}, {x1, y0}});
    world.push_back({{x1, y0}, {x1, y1}});
    world.push_back({{x1, y1}, {x0, y1}});
    world.push_back({{x0, y1}, {x0, y0}});
  };
  box(-4.2, -0.6, -3.4, 0.4);
  box(-6.5, 1.8, -5.9, 2.5);
  return world;
}

// The same with door niches along the hallway (one every 5 m, 1 m wide and 0.4 m deep): their
// jambs hold fits along the axis by a few dozen points.
std::vector<sm::testing::Segment> room_and_hallway_with_niches()
{
  auto world = furnished_room_and_hallway();
  for (const double x : {4.0, 9.0, 14.0, 19.0}) {
    const double side = x < 10.0 ? 1.0 : -1.0;
    world.push_back({{x, side}, {x, side * 1.4}});
    world.push_back({{x + 1.0, side}, {x + 1.0, side * 1.4}});
    world.push_back({{x, side * 1.4}, {x + 1.0, side * 1.4}});
  }
  return world;
}

// Round the room twice and 22 m down the hallway, with a 6 m laser, so that the hallway's axis
// is left to odometry (make_run: 2 % long, and odom_step_sigma at random).
SyntheticRun room_then_hallway(const std::vector<sm::testing::Segment>& world, double odom_step_sigma)
{
  sm::testing::LaserModel m;
  m.noise_m = 0.01;
  m.max_range = 6.0;
  return make_run(world, {{-6, -2}, {-1, -2}, {-1, 2}, {-6, 2}, {-6, -2}, {-1, -2}, {-1, 0}, {22, 0}}, 1, m,
                  odom_step_sigma);
}

// hallway_options with odometry's noise and scale learned as config/scan_mapper.yaml learns
// them, and with adapt_degeneracy the count set for the learned noise.
sm::ScanMapperOptions learning_options(bool adapt_degeneracy)
{
  auto o = hallway_options();
  o.odometry_noise.trans_per_m = 0.05;
  o.odometry_noise.min_trans_m = 0.002;
  o.odometry_noise.adapt_window_scans = 100;
  o.odometry_noise.adapt_degeneracy = adapt_degeneracy;
  o.odometry_scale.window_m = 50.0;
  return o;
}

struct HallwayOutcome
{
  double worst_along_m = 0.0;  // of the accepted scans' estimates in the hallway
  sm::MapperStats stats;
};

HallwayOutcome drive(const SyntheticRun& run, const sm::ScanMapperOptions& options)
{
  sm::ScanMapper mapper(options);
  HallwayOutcome out;
  for (size_t i = 0; i < run.scans.size(); ++i) {
    mapper.add_odometry({run.scans[i].utime, run.odom[i]});
    if (mapper.add_scan(run.scans[i]).accepted && run.truth[i].x() > 0.0)
      out.worst_along_m =
          std::max(out.worst_along_m, std::fabs(mapper.nodes().back().map_from_base.x() - run.truth[i].x()));
  }
  out.stats = mapper.stats();
  return out;
}

}  // namespace

TEST(OdometryBuffer, InterpolatesAndHoldsBriefly)
{
  sm::OdometryBuffer b;
  b.add({1000, {0, 0, 0}});
  b.add({2000, {1, 0, 0.2}});
  b.add({2000, {1.1, 0, 0.2}});  // same time: the later one wins
  b.add({1500, {9, 9, 9}});      // older than the newest: ignored
  EXPECT_FALSE(b.at(999, 0).has_value());
  EXPECT_NEAR(b.at(1500, 0)->x(), 0.55, 1e-12);
  EXPECT_NEAR(b.at(1500, 0)->theta(), 0.1, 1e-12);
  EXPECT_NEAR(b.at(2000, 0)->x(), 1.1, 1e-12);
  EXPECT_TRUE(b.at(2050, 100).has_value());
  EXPECT_FALSE(b.at(2200, 100).has_value());
}

TEST(ScanMapperOptions, LoadsAndRejectsBadValues)
{
  const auto ok = rgnav::config::Config::parse("scan_mapper:\n  gating:\n    min_travel_m: 0.3\n", "test");
  EXPECT_DOUBLE_EQ(sm::load_scan_mapper_options(ok.section("scan_mapper"), rgnav::config::RobotDescription{}).min_travel_m, 0.3);
  const auto bad = rgnav::config::Config::parse("scan_mapper:\n  gating:\n    min_travel_m: -1\n", "test");
  EXPECT_THROW(sm::load_scan_mapper_options(bad.section("scan_mapper"), rgnav::config::RobotDescription{}), rgnav::config::ConfigError);
  const auto sided = rgnav::config::Config::parse(
      "scan_mapper:\n  registration:\n    icp:\n      max_normal_angle_deg: 90\n  loop_closure:\n    max_rms_m: 0.03\n", "test");
  const auto so = sm::load_scan_mapper_options(sided.section("scan_mapper"), rgnav::config::RobotDescription{});
  EXPECT_DOUBLE_EQ(so.icp.max_normal_angle_deg, 90.0);
  EXPECT_DOUBLE_EQ(so.loop.max_rms_m, 0.03);
  const auto hall = rgnav::config::Config::parse("scan_mapper:\n  loop_closure:\n    degenerate_variance_m2: 50\n", "test");
  EXPECT_DOUBLE_EQ(sm::load_scan_mapper_options(hall.section("scan_mapper"), rgnav::config::RobotDescription{}).loop.degenerate_variance_m2, 50.0);
  const auto witness = rgnav::config::Config::parse(
      "scan_mapper:\n  loop_closure:\n    degenerate_keeps_graph_axis: true\n    degenerate_covariance_scale: 16\n", "test");
  const auto wo = sm::load_scan_mapper_options(witness.section("scan_mapper"), rgnav::config::RobotDescription{});
  EXPECT_TRUE(wo.loop.degenerate_keeps_graph_axis);
  EXPECT_DOUBLE_EQ(wo.loop.degenerate_covariance_scale, 16.0);
  const auto apart = rgnav::config::Config::parse("scan_mapper:\n  loop_closure:\n    witness_min_travel_m: 2.5\n", "test");
  EXPECT_DOUBLE_EQ(sm::load_scan_mapper_options(apart.section("scan_mapper"), rgnav::config::RobotDescription{}).loop.witness_min_travel_m, 2.5);
  const auto behind = rgnav::config::Config::parse("scan_mapper:\n  loop_closure:\n    witness_min_travel_m: -1\n", "test");
  EXPECT_THROW(sm::load_scan_mapper_options(behind.section("scan_mapper"), rgnav::config::RobotDescription{}), rgnav::config::ConfigError);
  const auto stronger = rgnav::config::Config::parse("scan_mapper:\n  loop_closure:\n    degenerate_covariance_scale: 0.5\n", "test");
  EXPECT_THROW(sm::load_scan_mapper_options(stronger.section("scan_mapper"), rgnav::config::RobotDescription{}), rgnav::config::ConfigError);
  const auto blunt = rgnav::config::Config::parse("scan_mapper:\n  registration:\n    icp:\n      max_normal_angle_deg: 200\n", "test");
  EXPECT_THROW(sm::load_scan_mapper_options(blunt.section("scan_mapper"), rgnav::config::RobotDescription{}), rgnav::config::ConfigError);
  const auto scaled = rgnav::config::Config::parse("scan_mapper:\n  odometry_scale:\n    window_m: 20\n", "test");
  EXPECT_DOUBLE_EQ(sm::load_scan_mapper_options(scaled.section("scan_mapper"), rgnav::config::RobotDescription{}).odometry_scale.window_m, 20.0);
  const auto loose = rgnav::config::Config::parse("scan_mapper:\n  odometry_scale:\n    max_error: 0.6\n", "test");
  EXPECT_THROW(sm::load_scan_mapper_options(loose.section("scan_mapper"), rgnav::config::RobotDescription{}), rgnav::config::ConfigError);
  const auto beam = rgnav::config::Config::parse(
      "scan_mapper:\n  points:\n    beam_normals:\n      max_gap_m: 0.8\n      max_bend_deg: 10\n"
      "  odometry_noise:\n    adapt:\n      degeneracy: true\n",
      "test");
  const auto bo = sm::load_scan_mapper_options(beam.section("scan_mapper"), rgnav::config::RobotDescription{});
  EXPECT_DOUBLE_EQ(bo.normals.beam_max_gap_m, 0.8);
  EXPECT_NEAR(bo.normals.beam_max_bend_rad, 10.0 * M_PI / 180.0, 1e-12);
  EXPECT_TRUE(bo.odometry_noise.adapt_degeneracy);
  const auto bent = rgnav::config::Config::parse("scan_mapper:\n  points:\n    beam_normals:\n      max_bend_deg: 60\n", "test");
  EXPECT_THROW(sm::load_scan_mapper_options(bent.section("scan_mapper"), rgnav::config::RobotDescription{}), rgnav::config::ConfigError);
  const auto typo = rgnav::config::Config::parse("scan_mapper:\n  gating:\n    min_travle_m: 0.3\n", "test");
  sm::load_scan_mapper_options(typo.section("scan_mapper"), rgnav::config::RobotDescription{});
  EXPECT_THROW(typo.finish(), rgnav::config::ConfigError);
  // The shipped config is valid and complete.
  const auto shipped = rgnav::config::Config::load(std::string(RGNAV_SOURCE_DIR) + "/config/scan_mapper.yaml");
  const auto robot = rgnav::config::load_robot_description_file(std::string(RGNAV_SOURCE_DIR) + "/config/robot.yaml");
  sm::load_scan_mapper_options(shipped.section("scan_mapper"), robot);
}

TEST(ScanMapperOptions, TheLaserMountIsTheRobotDescriptions)
{
  rgnav::config::RobotDescription robot;
  robot.laser_front.base_from_laser = sm::Pose2(0.3, -0.1, 0.5);
  const auto cfg = rgnav::config::Config::parse("scan_mapper:\n  gating:\n    min_travel_m: 0.3\n", "test");
  const auto o = sm::load_scan_mapper_options(cfg.section("scan_mapper"), robot);
  EXPECT_DOUBLE_EQ(o.base_from_laser.x(), 0.3);
  EXPECT_DOUBLE_EQ(o.base_from_laser.y(), -0.1);
  EXPECT_DOUBLE_EQ(o.base_from_laser.theta(), 0.5);
  // A copy of it in the mapper's config is refused as an unknown key.
  const auto copied = rgnav::config::Config::parse("scan_mapper:\n  base_from_laser: [0.12, 0.0, 0.0]\n", "test");
  sm::load_scan_mapper_options(copied.section("scan_mapper"), robot);
  EXPECT_THROW(copied.finish(), rgnav::config::ConfigError);
}

TEST(ScanMapper, GatesCorrectsDriftAndClosesTheLoop)
{
  const SyntheticRun run = make_run();
  sm::ScanMapper mapper(test_options());
  std::vector<int> accepted_index;  // run index of every node
  int corrections = 0;
  for (size_t i = 0; i < run.scans.size(); ++i) {
    mapper.add_odometry({run.scans[i].utime, run.odom[i]});
    const auto up = mapper.add_scan(run.scans[i]);
    if (up.accepted) accepted_index.push_back(static_cast<int>(i));
    corrections += static_cast<int>(up.corrected.size());
  }
  const auto& nodes = mapper.nodes();
  ASSERT_EQ(nodes.size(), accepted_index.size());
  EXPECT_LT(nodes.size(), run.scans.size() / 2);  // gating dropped most scans
  EXPECT_GT(nodes.size(), 50u);
  EXPECT_GE(mapper.stats().loop_closures, 1);
  EXPECT_EQ(mapper.stats().loop_rejected_strain, 0);  // closing a true loop after drift is no strain
  EXPECT_GT(corrections, 0);
  // Accuracy against the truth (the map frame = odometry frame at the first scan = truth there).
  std::vector<sm::Pose2> est, ref;
  std::vector<sm::TimedPose> timed;
  for (size_t k = 0; k < nodes.size(); ++k) {
    est.push_back(nodes[k].map_from_base);
    ref.push_back(run.truth[static_cast<size_t>(accepted_index[k])]);
    timed.push_back({nodes[k].scan.utime, ref.back()});
  }
  const auto err = sm::relation_error(est, ref, sm::select_relations(timed));
  EXPECT_LT(err.trans_mean_m, 0.02);
  EXPECT_LT(err.rot_mean_deg, 0.4);
  EXPECT_LT(sm::ate_rmse(est, ref), 0.05);
  // Raw odometry is far off by the end: the mapper did real work.
  EXPECT_GT(std::hypot(run.odom.back().x() - run.truth.back().x(), run.odom.back().y() - run.truth.back().y()), 0.5);
}

TEST(ScanMapper, ReportsProgressWithinAScansWork)
{
  // The node counts these as progress for the supervisor: under load one scan's registration
  // and loop search took the scan mapper past a 1 s bound on work without progress.
  const SyntheticRun run = make_run();
  sm::ScanMapper mapper(test_options());
  int calls = 0;
  mapper.set_progress([&calls] { ++calls; });
  int registered = 0, searched = 0;
  for (size_t i = 0; i < run.scans.size(); ++i) {
    mapper.add_odometry({run.scans[i].utime, run.odom[i]});
    const int before = calls;
    const int64_t attempts = mapper.stats().loop_attempts;
    const auto up = mapper.add_scan(run.scans[i]);
    if (!up.accepted || up.node == 0) {
      EXPECT_EQ(calls, before);   // a scan gated out does no work worth reporting
      continue;
    }
    ++registered;
    EXPECT_GE(calls - before, 1);
    // A loop search: before it, after the graph's uncertainty, after the correlative search.
    if (mapper.stats().loop_attempts > attempts) {
      ++searched;
      EXPECT_GE(calls - before, 4);
    }
  }
  EXPECT_GT(registered, 50);
  EXPECT_GT(searched, 0);
}

TEST(ScanMapper, HallwayClosuresDoNotDragTheEstimateAlongTheHallway)
{
  // A 2 m wide hallway with a few door niches, driven out and back: closures on the way back
  // mostly see the walls and a jamb or two, too few points to hold the hallway's axis.
  const SyntheticRun run = hallway_out_and_back(1);
  auto o = hallway_options();
  o.loop.degenerate_variance_m2 = 100.0;
  // As measured, with each hypothesis free to witness the next scan's. With witnesses from 1 m
  // on, the hypotheses gathered meanwhile are confirmed together, more closures of one stretch
  // count, and without the shipped config's axis rules (next test) they drag 2.0 m.
  o.loop.witness_min_travel_m = 0.0;
  sm::ScanMapper mapper(o);
  feed(run, &mapper);
  EXPECT_GT(mapper.stats().loop_closures, 0);
  // Back at the start, 48 m of 2 %-long odometry later. With 1 m^2 along the axis (the
  // sequential matches' figure) the 30-odd closures, each to a stretch a little off, added up to
  // 2.6 m along the hallway; with 100 m^2 they leave the axis to the sequential chain: 0.6 m.
  const sm::Pose2 last = mapper.nodes().back().map_from_base;
  EXPECT_LT(std::fabs(last.x() - run.truth.back().x()), 1.2);
  EXPECT_LT(std::fabs(last.y() - run.truth.back().y()), 0.1);
}

TEST(ScanMapper, HallwayClosuresKeepTheGraphsAxisAndCountAsOneWitness)
{
  // The hallway, driven out and back twice. A closure's fit does not hold the axis: where it
  // ends up along it is where the search stopped. With the axis kept from the graph and the
  // closures weighed as the one repeated witness they are, they correct across the axis and the
  // heading only. (Each setting alone, measured: 2.08 m axis kept, 0.61 m scaled.)
  const SyntheticRun run = hallway_out_and_back(2);
  auto along_axis_error = [&](bool keep_axis, double scale) {
    auto o = hallway_options();
    o.loop.degenerate_variance_m2 = 100.0;
    o.loop.degenerate_keeps_graph_axis = keep_axis;
    o.loop.degenerate_covariance_scale = scale;
    sm::ScanMapper mapper(o);
    feed(run, &mapper);
    EXPECT_GT(mapper.stats().loop_closures, 0);
    double worst = 0.0;
    size_t j = 0;   // nodes are a subset of the scans, in order
    for (const auto& n : mapper.nodes()) {
      while (run.scans[j].scan_id != n.scan.scan_id) ++j;
      worst = std::max(worst, std::fabs(n.map_from_base.x() - run.truth[j].x()));
    }
    return worst;
  };
  const double before = along_axis_error(false, 1.0);
  const double after = along_axis_error(true, 16.0);
  std::cout << "worst error along the hallway: " << before << " m as measured, " << after
            << " m with the axis kept and the closures weighed as one witness\n";
  EXPECT_LT(after, 0.5 * before);
}

TEST(ScanMapper, LearnsOdometrysScaleWhereTheScansHoldItAndUsesItAlongAHallway)
{
  // A furnished room, then a plain 2 m hallway off it, longer than the laser's 6 m: in the
  // hallway the scans leave the axis to odometry, which is 2 % long (make_run). Driven round
  // the room first, the mapper learns the scale there and drives the hallway on corrected
  // odometry.
  const SyntheticRun run = room_then_hallway(furnished_room_and_hallway(), 0.0);
  auto run_with = [&](double window_m) {
    auto o = hallway_options();
    o.odometry_scale.window_m = window_m;
    sm::ScanMapper mapper(o);
    feed(run, &mapper);
    return std::make_pair(mapper.nodes().back().map_from_base.x() - run.truth.back().x(), mapper.stats().odometry_scale);
  };
  const auto [learned_error, learned_scale] = run_with(50.0);
  const auto [raw_error, raw_scale] = run_with(0.0);
  std::cout << "along the hallway: " << learned_error << " m with the learned scale " << learned_scale << ", "
            << raw_error << " m without\n";
  EXPECT_NEAR(learned_scale, 1.0 / 1.02, 0.005);
  EXPECT_EQ(raw_scale, 1.0);
  // 22 m of hallway at 2 %: odometry alone would be 0.44 m long.
  EXPECT_GT(raw_error, 0.25) << "the hallway no longer leaves its axis to odometry: the test shows nothing";
  EXPECT_LT(std::fabs(learned_error), 0.1);
}

TEST(ScanMapper, APoorerOdometryLeavesFewerWeakestDirectionsToItself)
{
  // Every 5 cm step of odometry 60 % off at random: about 3.5 times the configured sigmas,
  // learned in the room. With adapt_degeneracy a fit needs that squared times fewer points to
  // hold its weakest direction, and fewer directions are left to odometry: those near the
  // jambs (between the niches the walls alone hold nothing along the axis, whatever the count).
  const SyntheticRun noisy = room_then_hallway(room_and_hallway_with_niches(), 0.6);
  auto o = learning_options(true);
  o.normals.beam_max_gap_m = 1.0;
  const HallwayOutcome adapted = drive(noisy, o);
  o.odometry_noise.adapt_degeneracy = false;
  const HallwayOutcome fixed = drive(noisy, o);
  std::cout << "weakest directions left to odometry: " << adapted.stats.axes_held << " for the learned scale "
            << adapted.stats.odometry_trans_scale << ", " << fixed.stats.axes_held << " for the fixed count; "
            << "worst error along the hallway " << adapted.worst_along_m << " and " << fixed.worst_along_m << " m\n";
  EXPECT_GT(adapted.stats.odometry_trans_scale, 2.0);
  EXPECT_GT(fixed.stats.axes_held, 50) << "the hallway holds its axis: the test shows nothing";
  EXPECT_LT(adapted.stats.axes_held, fixed.stats.axes_held * 3 / 4);

  // Odometry as good as configured learns no scale: the count and the estimates stay as they were.
  const SyntheticRun good = room_then_hallway(room_and_hallway_with_niches(), 0.0);
  const HallwayOutcome good_adapted = drive(good, learning_options(true));
  const HallwayOutcome good_fixed = drive(good, learning_options(false));
  EXPECT_EQ(good_adapted.stats.odometry_trans_scale, 1.0);
  EXPECT_EQ(good_adapted.stats.axes_held, good_fixed.stats.axes_held);
  EXPECT_EQ(good_adapted.worst_along_m, good_fixed.worst_along_m);
}

TEST(ScanMapper, SparseWallSamplesDoNotHoldTheFitAlongAHallway)
{
  // The fits trusted along the hallway, as in the test above. A 1 deg scanner samples the walls
  // ahead every few decimetres; without a normal from their neighbours such samples pair
  // point-to-point with the nearest sample of the same wall in the local map, hold the fit along
  // the axis and make it short. With the chord through their beam neighbours as their normal
  // they pair point-to-line.
  const SyntheticRun noisy = room_then_hallway(room_and_hallway_with_niches(), 0.6);
  auto o = learning_options(true);
  o.normals.beam_max_gap_m = 1.0;
  const HallwayOutcome beam = drive(noisy, o);
  o.normals.beam_max_gap_m = 0.0;
  const HallwayOutcome point = drive(noisy, o);
  std::cout << "worst error along the hallway: " << beam.worst_along_m << " m with beam normals, "
            << point.worst_along_m << " m without\n";
  EXPECT_GT(point.worst_along_m, 1.5) << "the sparse samples no longer drag the fit: the test shows nothing";
  EXPECT_LT(beam.worst_along_m, 0.5 * point.worst_along_m);
}

// A room with a door in its east wall (x = 0, 1 m wide) and, behind the door, a round bay: a
// half circle of 2.4 m radius about the door's middle (office_c of the IPA maps has ten).
std::vector<sm::testing::Segment> room_with_round_bay()
{
  std::vector<sm::testing::Segment> world = {{{-5, -2.5}, {0, -2.5}}, {{-5, 2.5}, {0, 2.5}}, {{-5, -2.5}, {-5, 2.5}},
                                             {{0, 0.5}, {0, 2.5}},    {{0, -2.5}, {0, -0.5}}};
  const double r = 2.4;
  for (int k = 0; k < 36; ++k) {
    const double a0 = -M_PI / 2 + M_PI * k / 36.0, a1 = -M_PI / 2 + M_PI * (k + 1) / 36.0;
    world.push_back({{r * std::cos(a0), r * std::sin(a0)}, {r * std::cos(a1), r * std::sin(a1)}});
  }
  return world;
}

TEST(ScanMapper, ARoundBaySeenFromItsDoorDoesNotTurnTheEstimate)
{
  // From the door the laser sees the bay's arc alone, which fits any heading about its centre.
  // The local map holds the part of the arc seen through the door from the room; turned so
  // that the wider arc seen now ends where the map's does, a fit gains a few inliers, and the
  // jambs give its Hessian a heading precision it does not have. Odometry's heading is the
  // better one there.
  sm::testing::LaserModel m;
  m.noise_m = 0.01;
  m.max_range = 8.0;
  const SyntheticRun run = make_run(room_with_round_bay(), {{-4, 0.2}, {1.2, 0.2}, {-4, 0.2}}, 1, m);
  auto run_with = [&](double turn_check_sigmas, double turn_min_inlier_gain = 0.05, double turn_max_rms_ratio = 0.0) {
    auto o = test_options();
    // As config/scan_mapper.yaml: a fit short of 90 % inliers is searched for again, +-45 deg.
    o.min_inlier_ratio = 0.9;
    o.local_window = {0.6, 45.0 * M_PI / 180};
    o.turn_check_sigmas = turn_check_sigmas;
    o.turn_min_inlier_gain = turn_min_inlier_gain;
    o.turn_max_rms_ratio = turn_max_rms_ratio;
    sm::ScanMapper mapper(o);
    double worst = 0.0;
    for (size_t i = 0; i < run.scans.size(); ++i) {
      mapper.add_odometry({run.scans[i].utime, run.odom[i]});
      if (mapper.add_scan(run.scans[i]).accepted)
        worst = std::max(
            worst, std::fabs(sm::normalize_angle(mapper.nodes().back().map_from_base.theta() - run.truth[i].theta())));
    }
    return std::make_pair(worst * 180 / M_PI, mapper.stats().turns_held);
  };
  const auto [checked_deg, held] = run_with(3.0);
  const auto [unchecked_deg, unheld] = run_with(0.0);
  EXPECT_GT(held, 0);
  EXPECT_EQ(unheld, 0);
  EXPECT_LT(checked_deg, 2.0);
  EXPECT_GT(unchecked_deg, 2 * checked_deg) << "the bay no longer turns the unchecked fit: the test shows nothing";

  // The precision test alone (no inlier gain asked): the turned fits fit the arc worse than
  // the fit at odometry's heading does (office_c: 0.022 m against 0.010 m).
  const auto [precise_deg, precise_held] = run_with(3.0, 0.0, 1.25);
  const auto [ungated_deg, ungated_held] = run_with(3.0, 0.0, 0.0);
  EXPECT_GT(precise_held, 0);
  EXPECT_EQ(ungated_held, 0);
  EXPECT_LT(precise_deg, 2.0);
  EXPECT_GT(ungated_deg, 2 * precise_deg) << "no turn gains nothing here: the precision test shows nothing";
}

TEST(ScanMapper, LearnsHowNoisyTheOdometryIs)
{
  // The translation sigmas of good odometry (config/scan_mapper.yaml: 2 mm + 5 %); the scale on
  // them is learned from the matches. A 2 % scale error is within them; a random error of 60 %
  // of every 5 cm step (6 cm, 30 %, over a 0.2 m gate, along the drive only) is about 3.5 times
  // their 1.2 cm per axis, less what the fits' own covariance explains.
  sm::testing::LaserModel m;
  m.noise_m = 0.01;
  const std::vector<Eigen::Vector2d> loop = {{1, 0}, {10, 0}, {10, 4}, {1, 4.5}, {1, 0}};
  auto learned_scale = [&](double odom_step_sigma, int window) {
    const SyntheticRun run = make_run(sm::testing::office_world(), loop, 1, m, odom_step_sigma);
    auto o = test_options();
    o.odometry_noise.trans_per_m = 0.05;
    o.odometry_noise.min_trans_m = 0.002;
    o.odometry_noise.adapt_window_scans = window;
    sm::ScanMapper mapper(o);
    feed(run, &mapper);
    return mapper.stats().odometry_trans_scale;
  };
  const double clean = learned_scale(0.0, 100);
  const double noisy = learned_scale(0.6, 100);
  EXPECT_LT(clean, 1.2);
  EXPECT_GT(noisy, 1.8);
  EXPECT_LT(noisy, 4.0);
  EXPECT_EQ(learned_scale(0.6, 0), 1.0) << "adapt_window_scans 0 is off";
}

TEST(ScanMapper, IsDeterministic)
{
  const SyntheticRun run = make_run();
  auto once = [&] {
    sm::ScanMapper mapper(test_options());
    feed(run, &mapper);
    return mapper.nodes();
  };
  const auto a = once(), b = once();
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].map_from_base.x(), b[k].map_from_base.x());
    EXPECT_EQ(a[k].map_from_base.theta(), b[k].map_from_base.theta());
  }
}

TEST(ScanMapper, ScansWithoutOdometryAreCountedNotUsed)
{
  sm::ScanMapper mapper(test_options());
  const SyntheticRun run = make_run();
  EXPECT_FALSE(mapper.add_scan(run.scans[0]).accepted);
  EXPECT_EQ(mapper.stats().no_odometry, 1);
}

TEST(MapperState, SaveLoadRoundTripAndResume)
{
  const SyntheticRun run = make_run();
  const size_t half = run.scans.size() / 2;
  sm::ScanMapper first(test_options());
  for (size_t i = 0; i < half; ++i) {
    first.add_odometry({run.scans[i].utime, run.odom[i]});
    first.add_scan(run.scans[i]);
  }
  const auto dir = fs::temp_directory_path() / ("rgnav_sm_state_" + std::to_string(::getpid()));
  const auto path = (dir / "state.bin").string();
  sm::save_state(first.state(), path);
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  const auto loaded = sm::load_state(path);
  ASSERT_TRUE(loaded.has_value());
  ASSERT_EQ(loaded->nodes.size(), first.nodes().size());
  ASSERT_EQ(loaded->edges.size(), first.graph().edges().size());
  EXPECT_EQ(loaded->nodes.back().scan.ranges, first.nodes().back().scan.ranges);
  EXPECT_EQ(loaded->nodes.back().map_from_base.x(), first.nodes().back().map_from_base.x());

  // Resume with an odometry origin that moved (driver restarted): the first scan relocalises.
  sm::ScanMapper resumed(test_options(), *loaded);
  const sm::Pose2 new_origin_from_old = sm::Pose2{5, -3, 1.0}.inverse();
  for (size_t i = half; i < run.scans.size(); ++i) {
    resumed.add_odometry({run.scans[i].utime, new_origin_from_old * run.odom[i]});
    resumed.add_scan(run.scans[i]);
  }
  ASSERT_GT(resumed.nodes().size(), loaded->nodes.size() + 10);
  // Every resumed node is still in the map frame of the first run (truth = map frame).
  size_t j = half;
  for (size_t k = loaded->nodes.size(); k < resumed.nodes().size(); ++k) {
    const auto& n = resumed.nodes()[k];
    while (run.scans[j].scan_id != n.scan.scan_id) ++j;
    EXPECT_LT(std::hypot(n.map_from_base.x() - run.truth[j].x(), n.map_from_base.y() - run.truth[j].y()), 0.15) << k;
  }
  fs::remove_all(dir);
}

TEST(MapperState, DamagedFilesAreRefused)
{
  const auto dir = fs::temp_directory_path() / ("rgnav_sm_state_bad_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  EXPECT_FALSE(sm::load_state((dir / "missing.bin").string()).has_value());
  const SyntheticRun run = make_run();
  sm::ScanMapper m(test_options());
  for (size_t i = 0; i < 60; ++i) {
    m.add_odometry({run.scans[i].utime, run.odom[i]});
    m.add_scan(run.scans[i]);
  }
  const auto path = (dir / "state.bin").string();
  sm::save_state(m.state(), path);
  const auto size = fs::file_size(path);
  fs::copy_file(path, dir / "cut.bin");
  fs::resize_file(dir / "cut.bin", size - 10);
  EXPECT_THROW(sm::load_state((dir / "cut.bin").string()), std::runtime_error);
  fs::copy_file(path, dir / "flip.bin");
  {
    std::fstream f(dir / "flip.bin", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(size / 2));
    f.put('\x5a');
  }
  EXPECT_THROW(sm::load_state((dir / "flip.bin").string()), std::runtime_error);
  std::ofstream(dir / "junk.bin") << "not a state file at all, but long enough to have a header";
  EXPECT_THROW(sm::load_state((dir / "junk.bin").string()), std::runtime_error);
  fs::remove_all(dir);
}
