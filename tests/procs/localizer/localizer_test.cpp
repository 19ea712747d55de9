// The localizer's algorithm library (procs/localizer, no LCM) on the hand-made two-room map:
// distance field, resampling, tracking across the door with the hand-over and its
// gateway-passed event, global localization, kidnap detection and recovery, a map merge; and
// on two rooms that look alike (twin_rooms.h): a claim only from what the path has shown.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/pose_track.h"
#include "localizer/likelihood_field.h"
#include "localizer/localizer.h"
#include "localizer/path_score.h"
#include "localizer/path_search.h"
#include "localizer/resampling.h"
#include "twin_rooms.h"
#include "two_room_map.h"

namespace rgnav::localizer {
namespace {

using Eigen::Vector2d;
using geometry::Pose2;

const Pose2 kLaser(0.12, 0, 0);

LocalizerOptions options()
{
  LocalizerOptions o;
  o.base_from_laser = kLaser;
  o.seed = 3;
  o.global.min_travel = 0.5;
  return o;
}

// A drive along straight legs between the given map-frame poses, one scan every 5 cm / 2 deg,
// with perfect odometry (odom frame = map frame shifted, so nothing relies on them being equal).
struct Drive
{
  const testing::Walls& walls;
  Localizer& loc;
  Pose2 odom_from_map{1.0, -2.0, 0.3};
  int64_t utime = 1'000'000;
  int64_t scan_id = 1;
  Pose2 truth{};
  bool updated = false;   // the last scan updated the filter

  void to(const Pose2& goal, const std::function<void()>& after_scan = nullptr)
  {
    const Pose2 start = truth;
    const double d = (goal.translation() - start.translation()).norm();
    const double turn = std::fabs(geometry::normalize_angle(goal.theta() - start.theta()));
    const int steps = std::max(1, static_cast<int>(std::ceil(std::max(d / 0.05, turn / (2 * M_PI / 180)))));
    for (int k = 1; k <= steps; ++k) {
      truth = geometry::interpolate(start, goal, static_cast<double>(k) / steps);
      utime += 40'000;
      updated = loc.update(testing::cast_scan(walls, truth, kLaser, utime, scan_id++), odom_from_map * truth);
      if (after_scan) after_scan();
    }
  }

  // The twin-room drive: facing the room's bottom-right corner, a step on, a turn, and across
  // the room (room_a's; `dx` east of it: room_b at 10).
  void across_twin_room(double dx = 0.0)
  {
    truth = Pose2(2.4 + dx, 1.4, -0.6);
    to(truth);
    to(Pose2(2.6 + dx, 1.2, -0.6));
    to(Pose2(2.6 + dx, 1.2, 2.5));
    to(Pose2(1.8 + dx, 1.8, 2.5));
    to(Pose2(1.6 + dx, 1.95, 2.5));
  }
};

Pose2 in_region(const testing::TwoRoomWorld& w, int64_t region, const Pose2& map_pose)
{
  return w.map.region(region)->map_from_region.inverse() * map_pose;
}

double error_m(const testing::TwoRoomWorld& w, const Estimate& e, const Pose2& truth)
{
  return (e.region_from_base.translation() - in_region(w, e.region, truth).translation()).norm();
}

TEST(LikelihoodField, DistanceToTheNearestLine)
{
  rgmap::LineSegment s;
  s.a = {0, 0};
  s.b = {2, 0};
  const LikelihoodField f({s}, 0.02, 1.0, 1.0);
  EXPECT_LT(f.distance({1.0, 0.0}), 0.03);
  EXPECT_NEAR(f.distance({1.0, 0.5}), 0.5, 0.03);
  EXPECT_NEAR(f.distance({-0.3, -0.4}), 0.5, 0.03);   // beyond the end: to the end point
  EXPECT_FLOAT_EQ(f.distance({50, 50}), 1.0f);        // off the field: saturated
}

// The searches' shared pieces: views spread over a path keep its first and last, no index twice;
// points turned per heading.
TEST(GlobalSearch, SpreadIndicesAndTurnedPoints)
{
  EXPECT_EQ(spread_indices(10, 4), (std::vector<size_t>{0, 3, 6, 9}));
  EXPECT_EQ(spread_indices(2, 4), (std::vector<size_t>{0, 1}));
  EXPECT_EQ(spread_indices(5, 1), (std::vector<size_t>{4}));
  EXPECT_TRUE(spread_indices(0, 3).empty());
  const auto turned = rotated_per_heading({Eigen::Vector2d(1, 0)}, 4);
  ASSERT_EQ(turned.size(), 4u);
  EXPECT_LT((turned[1][0] - Eigen::Vector2d(0, 1)).norm(), 1e-12);
  EXPECT_LT((turned[2][0] - Eigen::Vector2d(-1, 0)).norm(), 1e-12);
}

TEST(Resampling, KldCountGrowsWithTheBinsAndIsClamped)
{
  ParticleCount o;
  o.min = 100;
  o.max = 5000;
  EXPECT_EQ(kld_sample_count(1, o), 100);
  EXPECT_LT(kld_sample_count(10, o), kld_sample_count(100, o));
  EXPECT_EQ(kld_sample_count(100000, o), 5000);
}

TEST(Resampling, LowVarianceDrawsInProportionToTheWeights)
{
  std::mt19937_64 rng(1);
  const auto idx = low_variance_resample({1.0, 3.0, 0.0}, 400, rng);
  ASSERT_EQ(idx.size(), 400u);
  const auto ones = std::count(idx.begin(), idx.end(), 1u);
  EXPECT_NEAR(static_cast<double>(ones), 300.0, 1.0);
  EXPECT_EQ(std::count(idx.begin(), idx.end(), 2u), 0);
}

TEST(Localizer, TracksThroughTheDoorAndReportsTheGatewayPassed)
{
  const auto w = testing::two_room_world();
  Localizer loc(options());
  loc.set_map(w.map);
  Drive drive{w.walls, loc};
  drive.truth = Pose2(2.0, 1.5, 0.0);
  ASSERT_TRUE(loc.set_pose(w.room_a, in_region(w, w.room_a, drive.truth), 0.05, 0.03));
  double worst = 0;
  std::vector<GatewayPassed> passed;
  drive.to(Pose2(6.5, 1.5, 0.0), [&] {
    // Measured at the filter's updates: between them the estimate stands still (travel gate).
    if (drive.updated) worst = std::max(worst, error_m(w, loc.estimate(), drive.truth));
    for (const auto& e : loc.take_gateway_events()) passed.push_back(e);
  });
  EXPECT_EQ(loc.mode(), Mode::kTracking);
  EXPECT_EQ(loc.estimate().region, w.room_b);
  EXPECT_LT(worst, 0.03);
  EXPECT_GE(loc.stats().handovers, 1);
  ASSERT_EQ(passed.size(), 1u);
  EXPECT_EQ(passed[0].gateway, w.door);
  EXPECT_EQ(passed[0].from_region, w.room_a);
  EXPECT_EQ(passed[0].to_region, w.room_b);
  EXPECT_GE(passed[0].distance_past, options().gateway_passed_distance);
  // map_from_base is the region pose placed by the region's frame.
  const auto& e = loc.estimate();
  EXPECT_LT((e.map_from_base.translation() - drive.truth.translation()).norm(), 0.11);   // up to one gate of travel behind
  EXPECT_GT(e.confidence, 0.5);
}

// A view of the path is scored in the region that holds the place it was taken from: a pose in
// room_a given in room_b's frame is found in room_a, at the same map-frame place.
TEST(PathScore, AViewIsScoredInTheRegionHoldingItsPlace)
{
  const auto w = testing::two_room_world();
  RegionMaps maps;
  maps.set_map(w.map);
  const Pose2 in_a(2.0, 1.5, 0.3);   // map frame = room_a's frame
  const Pose2 seen_from_b = in_region(w, w.room_b, in_a);
  const auto [held, pose] = holding_region(maps, w.room_b, seen_from_b, 0.3);
  ASSERT_NE(held, nullptr);
  EXPECT_EQ(held->id, w.room_a);
  EXPECT_LT((pose.translation() - in_a.translation()).norm(), 1e-9);
  EXPECT_EQ(holding_region(maps, w.room_b, seen_from_b, 0.3, 0).first->id, w.room_b);   // no gateway crossed: its own region
  // A path from room_a into room_b scores the same at the true pose whichever room's frame asks.
  const BeamScorer scorer(0.2, 0.9, 0.1, 1.0);
  const auto scan_points = [&](const Pose2& map_pose) {
    return beam_end_points(testing::cast_scan(w.walls, map_pose, kLaser, 1, 1), kLaser, 30);
  };
  const Pose2 then(2.0, 1.5, 0.0), now(6.0, 1.5, 0.0);
  const auto p_then = scan_points(then), p_now = scan_points(now);
  const std::vector<PlacedView> views{{now.between(then), &p_then}, {Pose2(), &p_now}};
  const double truth = path_score(maps, scorer, w.room_b, in_region(w, w.room_b, now), views, 0.3);
  EXPECT_GT(truth, -0.05 * static_cast<double>(p_then.size() + p_now.size()));   // nearly every point on a wall
  EXPECT_LT(path_score(maps, scorer, w.room_b, in_region(w, w.room_b, Pose2(6.0, 0.9, 0.0)), views, 0.3), truth - 5.0);
}

// A beam from room_a through the door that ends in the middle of room_b, far from any line:
// room_b's scans carved that spot free, so the stacked map (room_a's lines and room_b's beyond
// the door) says "no wall there" and judges the beam. Judged in room_a's own freespace only, the
// beam leaves it at the door, where no line is, and would count as unjudged: a look-alike place
// whose map has a wall there could not be told apart on it.
TEST(PathScore, ABeamThroughAGatewayIsJudgedInTheNeighboursFreespace)
{
  const auto w = testing::two_room_world();
  RegionMaps maps;
  maps.set_map(w.map);
  const BeamScorer scorer(0.2, 0.9, 0.1, 1.0);
  const Pose2 here(2.0, 1.5, 0.0);   // room_a (its frame = the map frame), facing the door
  const std::vector<Vector2d> through_door{Vector2d(4.5, 0.0)};   // ends at map (6.5, 1.5), 1.5 m from room_b's walls
  const std::vector<Vector2d> at_wall{Vector2d(0.0, 1.5)};        // ends on room_a's top wall
  for (const bool stacked : {true, false}) {
    SCOPED_TRACE(stacked ? "stacked freespace" : "own freespace");
    const auto fits = [&](const std::vector<Vector2d>& points) {
      return path_beam_fits(maps, scorer, w.room_a, here, {{Pose2(), &points}}, 0.3, 0.2, stacked);
    };
    EXPECT_EQ(fits(through_door).front().known, stacked);
    EXPECT_TRUE(fits(at_wall).front().known);   // near a line: judged either way
  }
}

TEST(Localizer, FindsItselfFromAnUnknownPoseWhileDriving)
{
  const auto w = testing::two_room_world();
  Localizer loc(options());
  loc.set_map(w.map);
  EXPECT_EQ(loc.mode(), Mode::kUnknown);
  Drive drive{w.walls, loc};
  drive.truth = Pose2(7.0, 0.0, 2.0);
  drive.to(Pose2(7.0, 0.0, 2.0));   // one scan: candidates everywhere, not yet sure
  EXPECT_EQ(loc.mode(), Mode::kGlobal);
  drive.to(Pose2(6.5, 1.2, 2.0));
  drive.to(Pose2(6.5, 1.2, 3.0));
  EXPECT_EQ(loc.mode(), Mode::kTracking);
  EXPECT_EQ(loc.estimate().region, w.room_b);
  EXPECT_LT(error_m(w, loc.estimate(), drive.truth), 0.05);
}

// The robot first looks at the one corner that tells the twin rooms apart, then turns away and
// drives on: its current view fits both rooms equally, the views of its path only room_a. The
// claim must come from the path (a test of the current scan alone never claims here).
TEST(Localizer, ClaimsThePlaceTheViewsOfItsPathTellApart)
{
  const auto w = testing::twin_room_world(true);
  // No claim before the telling corner is out of view (it leaves the view about 1 m into the
  // drive, turns counted): then the current view alone cannot tell the rooms apart.
  auto o = options();
  o.global.min_travel = 1.2;
  const auto drive_past_the_corner = [&w](Localizer& loc) {
    loc.set_map(w.map);
    Drive drive{w.walls, loc};
    drive.truth = Pose2(2.4, 1.4, -0.6);   // facing the bottom-right corner: square in room_a, cut off in room_b
    drive.to(drive.truth);
    drive.to(Pose2(2.6, 1.2, -0.6));
    EXPECT_EQ(loc.mode(), Mode::kGlobal);  // not yet driven far enough to claim
    drive.to(Pose2(2.6, 1.2, 2.5));        // turn to the other cut corner: the telling one is behind now
    drive.to(Pose2(1.8, 1.8, 2.5));
    drive.to(Pose2(1.6, 1.95, 2.5));
    return drive.truth;
  };
  Localizer loc(o);
  const Pose2 truth = drive_past_the_corner(loc);
  EXPECT_EQ(loc.mode(), Mode::kTracking);
  EXPECT_EQ(loc.estimate().region, w.room_a);
  EXPECT_LT((loc.estimate().region_from_base.translation() - truth.translation()).norm(), 0.05);
  // The rule switched off (the path holds the current view only): the view fits both rooms,
  // and the localizer never claims.
  auto one_view = o;
  one_view.global.view_path_length = 0;
  Localizer forgetful(one_view);
  drive_past_the_corner(forgetful);
  EXPECT_EQ(forgetful.mode(), Mode::kGlobal);
}

// The same drive in rooms with nothing to tell them apart: the localizer stays unsure, and the
// true pose is not distinguishable from its twin (what the benchmark counts as ambiguous).
TEST(Localizer, StaysUnsureWhereTheMapRepeatsItself)
{
  const auto w = testing::twin_room_world(false);
  Localizer loc(options());
  loc.set_map(w.map);
  Drive drive{w.walls, loc};
  drive.across_twin_room();
  EXPECT_EQ(loc.mode(), Mode::kGlobal);
  EXPECT_FALSE(loc.distinguishable(w.room_a, drive.truth));
  EXPECT_FALSE(loc.distinguishable(w.room_b, drive.truth));   // region frames: the same spot in either room
  // The claim test's numbers say why: the twin room's spot, 10 m away, leads or trails by less
  // than the margin, counted on every beam of the path (both rooms' maps judge them all).
  ClaimTest twin;
  loc.why_not_distinguishable(w.room_a, drive.truth, &twin);
  EXPECT_LT(std::fabs(twin.lead), twin.margin);
  EXPECT_NEAR(twin.rival_distance, 10.0, 0.3);
  EXPECT_EQ(twin.judged_beams, twin.beams);
  EXPECT_GT(twin.views, 1);
}

// The scan search keeps one place here (hypotheses = 1), so its rivals never hold the twin room:
// the claim test of the newest search's places alone claims one of two identical rooms, a
// guess. The search of every place on the path's views finds the twin, and the claim waits.
TEST(Localizer, AClaimWaitsForATwinTheScanSearchDidNotKeep)
{
  const auto w = testing::twin_room_world(false);
  auto o = options();
  o.global.hypotheses = 1;
  const auto drive_in_room_a = [&w](Localizer& loc) {
    loc.set_map(w.map);
    Drive drive{w.walls, loc};
    drive.across_twin_room();
  };
  Localizer loc(o);
  drive_in_room_a(loc);
  EXPECT_EQ(loc.mode(), Mode::kGlobal);
  EXPECT_GT(loc.stats().path_searches, 0);
  auto scan_rivals_only = o;
  scan_rivals_only.global.claim_path_search = false;
  Localizer guesser(scan_rivals_only);
  drive_in_room_a(guesser);
  EXPECT_EQ(guesser.mode(), Mode::kTracking);   // claimed a room the views cannot tell
}

// Twin rooms alike in the world, room_b's map missing the cabinet (twin_room_world_with_map_gap):
// the robot in room_b looks at the cabinet, which room_a's map explains and room_b's does not.
// On all beams room_a wins by the cabinet's: the rule that counts every beam claims room_a, 10 m
// wrong. On the beams both maps can judge, the rooms fit alike and the claim waits.
TEST(Localizer, AWallMissingFromOneMapIsNoEvidenceForItsTwin)
{
  const auto w = testing::twin_room_world_with_map_gap();
  const auto drive_in_room_b = [&w](Localizer& loc) {
    loc.set_map(w.map);
    Drive drive{w.walls, loc};
    drive.across_twin_room(10.0);
    drive.to(Pose2(11.6, 1.5, 3.5));
  };
  Localizer loc(options());
  drive_in_room_b(loc);
  EXPECT_FALSE(loc.mode() == Mode::kTracking && loc.estimate().region == w.room_a);
  auto all_beams = options();
  all_beams.global.claim_judged_beams = false;
  Localizer fooled(all_beams);
  drive_in_room_b(fooled);
  EXPECT_EQ(fooled.mode(), Mode::kTracking);
  EXPECT_EQ(fooled.estimate().region, w.room_a);
}

// The whole-path search on the twin rooms: the best place is the true one, in the room whose
// corner the path saw; the twin room's same spot is found too, scoring worse by what that
// corner adds; where nothing tells the rooms apart both score alike.
TEST(PathSearch, FindsEveryPlaceThePathFitsBestFirst)
{
  const auto path_places_in = [](const testing::TwinRoomWorld& w) {
    RegionMaps maps;
    maps.set_map(w.map);
    const BeamScorer scorer(0.2, 0.9, 0.1, 1.0);
    const Pose2 then(2.4, 1.4, -0.6), mid(2.6, 1.2, 2.5), now(1.6, 1.95, 2.5);   // room_a, map frame
    const auto scan_points = [&](const Pose2& map_pose) {
      return beam_end_points(testing::cast_scan(w.walls, map_pose, kLaser, 1, 1), kLaser, 30);
    };
    static std::vector<Vector2d> p_then, p_mid, p_now;
    p_then = scan_points(then);
    p_mid = scan_points(mid);
    p_now = scan_points(now);
    const std::vector<PlacedView> views{{now.between(then), &p_then}, {now.between(mid), &p_mid}, {Pose2(), &p_now}};
    const auto distinct = [&](const Hypothesis& a, const Hypothesis& b) {
      const Pose2 pa = maps.region(a.region)->map_from_region * a.region_from_base;
      const Pose2 pb = maps.region(b.region)->map_from_region * b.region_from_base;
      return (pa.translation() - pb.translation()).norm() > 1.0 || std::fabs(geometry::normalize_angle(pa.theta() - pb.theta())) > 0.5;
    };
    int progress = 0;   // one report per region searched (the node's heartbeat shows the work going on)
    auto places = path_search(maps, views, scorer, PathSearchOptions{}, distinct, [&progress] { ++progress; });
    EXPECT_EQ(progress, static_cast<int>(maps.regions().size()));
    return std::make_pair(std::move(places), now);
  };
  const auto near = [](const Hypothesis& h, const Pose2& p) {
    return (h.region_from_base.translation() - p.translation()).norm() < 0.3 &&
           std::fabs(geometry::normalize_angle(h.region_from_base.theta() - p.theta())) < 6 * M_PI / 180;
  };
  const auto twin_of = [&](const std::vector<Hypothesis>& places, int64_t region, const Pose2& p) {
    return std::find_if(places.begin(), places.end(), [&](const Hypothesis& h) { return h.region == region && near(h, p); });
  };
  {
    const auto w = testing::twin_room_world(true);
    const auto [places, now] = path_places_in(w);
    ASSERT_GE(places.size(), 2u);
    EXPECT_EQ(places.front().region, w.room_a);
    EXPECT_TRUE(near(places.front(), now));   // room frames sit at the rooms' corners: the map pose in room_a
    const auto twin = twin_of(places, w.room_b, now);
    ASSERT_NE(twin, places.end());
    EXPECT_LT(twin->score, places.front().score - 5.0);
  }
  {
    const auto w = testing::twin_room_world(false);
    const auto [places, now] = path_places_in(w);
    const auto a = twin_of(places, w.room_a, now), b = twin_of(places, w.room_b, now);
    ASSERT_NE(a, places.end());
    ASSERT_NE(b, places.end());
    EXPECT_NEAR(a->score, b->score, 2.0);
  }
}

TEST(Localizer, FlagsAKidnapAndRelocalizes)
{
  const auto w = testing::two_room_world();
  Localizer loc(options());
  loc.set_map(w.map);
  Drive drive{w.walls, loc};
  drive.truth = Pose2(1.5, 1.0, 0.5);
  ASSERT_TRUE(loc.set_pose(w.room_a, in_region(w, w.room_a, drive.truth), 0.05, 0.03));
  drive.to(Pose2(2.5, 1.5, 0.5));
  ASSERT_LT(error_m(w, loc.estimate(), drive.truth), 0.05);
  EXPECT_FALSE(loc.take_kidnap_flag());
  // Carried into the other room; the odometry knows nothing of it.
  const Pose2 odom_before = drive.odom_from_map * drive.truth;
  drive.odom_from_map = odom_before * Pose2(7.5, 2.0, -2.5).inverse();
  drive.truth = Pose2(7.5, 2.0, -2.5);
  bool flagged = false;
  int scans_to_flag = 0;
  drive.to(Pose2(6.5, 0.5, -2.5), [&] {
    if (!flagged) ++scans_to_flag;
    flagged = flagged || loc.take_kidnap_flag();

  });
  EXPECT_TRUE(flagged);
  EXPECT_LE(scans_to_flag * 0.04, options().recovery.kidnap_after_s + 0.2);
  drive.to(Pose2(6.0, 1.5, -1.0));
  EXPECT_EQ(loc.mode(), Mode::kTracking);
  EXPECT_EQ(loc.estimate().region, w.room_b);
  EXPECT_LT(error_m(w, loc.estimate(), drive.truth), 0.05);
}

TEST(Localizer, ANewMapVersionDoesNotMoveThePose)
{
  auto w = testing::two_room_world();
  Localizer loc(options());
  loc.set_map(w.map);
  Drive drive{w.walls, loc};
  drive.truth = Pose2(6.0, 1.0, 1.0);
  ASSERT_TRUE(loc.set_pose(w.room_b, in_region(w, w.room_b, drive.truth), 0.05, 0.03));
  drive.to(Pose2(6.5, 1.0, 1.0));
  const Pose2 before = loc.estimate().map_from_base;
  // room_b merged into room_a (the same place seen twice): its particles go to room_a's frame.
  auto merged = w.map;
  const Pose2 a_from_b = merged.region(w.room_a)->map_from_region.inverse() * merged.region(w.room_b)->map_from_region;
  merged.merge(w.room_b, w.room_a, a_from_b, drive.utime);
  ++merged.version;
  loc.set_map(merged);
  EXPECT_EQ(loc.estimate().region, w.room_a);
  EXPECT_LT((loc.estimate().map_from_base.translation() - before.translation()).norm(), 1e-6);
  for (const auto& p : loc.particles()) EXPECT_EQ(p.region, w.room_a);
}

}  // namespace
}  // namespace rgnav::localizer
