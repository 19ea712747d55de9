#include <gtest/gtest.h>

#include "gateway_detector/gateway_detector.h"
#include "synthetic.h"

namespace rgnav::gateway_detector {
namespace {

using test::cast;

struct Drive
{
  std::vector<GatewayEvent> events;
  std::vector<FinishedSequence> sequences;
  int scans_with_hypotheses = 0;
};

// Drives along +x from x0 to x1 (laser at the base origin), one scan every `step` metres.
Drive drive(GatewayDetector& det, const test::Walls& walls, double x0, double x1, double step, double y = 0.0)
{
  Drive d;
  int64_t id = 1;
  for (double x = x0; x <= x1; x += step, ++id) {
    PosedScan ps;
    ps.map_from_base = geometry::Pose2(x, y, 0.0);
    ps.scan = cast(walls, ps.map_from_laser(), 0.005, static_cast<unsigned>(id));
    ps.scan.scan_id = id;
    ps.scan.utime = id * 13333;
    const auto out = det.process(ps);
    d.scans_with_hypotheses += !out.hypotheses.empty();
    d.events.insert(d.events.end(), out.events.begin(), out.events.end());
    const auto fin = det.take_finished_sequences();
    d.sequences.insert(d.sequences.end(), fin.begin(), fin.end());
  }
  return d;
}

TEST(Tracking, DriveThroughADoorGivesApproachedEnteredTraversed)
{
  DetectorOptions o;
  o.detect_crossings = false;
  GatewayDetector det(o);
  // 75 Hz at 0.5 m/s: 6.7 mm between scans; the frame leaves the field of view well before
  // the robot is in the door, so the track must be held.
  const auto d = drive(det, test::door(2.0, 0.9), -1.0, 3.5, 0.0067);
  std::vector<EventKind> kinds;
  int64_t track = -1;
  for (const auto& e : d.events) {
    if (track < 0) track = e.track_id;
    EXPECT_EQ(e.track_id, track);
    EXPECT_EQ(e.gateway_class, kOutNarrowPassage);
    kinds.push_back(e.kind);
  }
  ASSERT_EQ(kinds, (std::vector<EventKind>{EventKind::kApproached, EventKind::kEntered, EventKind::kTraversed}));
  // The traversal heading and the gateway points in the map frame.
  EXPECT_NEAR(d.events[2].direction, 0.0, 1e-9);
  ASSERT_EQ(d.events[2].gateway_points.size(), 2u);
  for (const auto& p : d.events[2].gateway_points) {
    EXPECT_NEAR(p.x(), 2.0, 0.05);
    EXPECT_NEAR(std::fabs(p.y()), 0.45, 0.06);
  }
}

TEST(Tracking, TurningBackBeforeTheDoorIsLost)
{
  DetectorOptions o;
  o.detect_crossings = false;
  GatewayDetector det(o);
  // Approach to 1.2 m, then back off: approached, then lost (never entered).
  auto d = drive(det, test::door(2.0, 0.9), -0.5, 0.8, 0.02);
  int64_t id = 1000;
  for (double x = 0.8; x >= -3.0; x -= 0.02, ++id) {
    PosedScan ps;
    ps.map_from_base = geometry::Pose2(x, 0.0, M_PI);  // turned around: the door is out of view
    ps.scan = cast(test::door(2.0, 0.9), ps.map_from_laser());
    ps.scan.scan_id = id;
    const auto out = det.process(ps);
    d.events.insert(d.events.end(), out.events.begin(), out.events.end());
  }
  ASSERT_EQ(d.events.size(), 2u);
  EXPECT_EQ(d.events[0].kind, EventKind::kApproached);
  EXPECT_EQ(d.events[1].kind, EventKind::kLost);
}

TEST(Tracking, ApproachingACrossingGivesOneSequencePerHypothesisAndEvents)
{
  DetectorOptions o;
  o.detect_narrow_passages = false;
  GatewayDetector det(o);
  // T-crossing at x in [0, 2]; drive from 8 m before it into it and out to the left would need
  // a turn; driving straight ends at the front wall, so stop inside the crossing.
  const auto d = drive(det, test::crossing(kT, 2.0), -8.0, 0.9, 0.05);
  ASSERT_FALSE(d.sequences.empty());
  // The main track's sequence: many observations, distance decreasing, classified T by SOC.
  const auto longest = std::max_element(d.sequences.begin(), d.sequences.end(),
                                        [](const auto& a, const auto& b) { return a.sequence.size() < b.sequence.size(); });
  EXPECT_GE(longest->sequence.size(), 30u);
  EXPECT_TRUE(longest->entered);
  EXPECT_LE(longest->sequence.front().distance, o.tracking.sequence_start_distance);
  for (size_t i = 1; i < longest->sequence.size(); ++i)
    EXPECT_LE(longest->sequence[i].distance, longest->sequence[i - 1].distance + 0.05);
  EXPECT_EQ(soc_last(longest->sequence), kT);
  EXPECT_EQ(asc(longest->sequence), kT);
  // Every sequence of this crossing ends when the robot enters it.
  for (const auto& q : d.sequences)
    if (q.sequence.size() > 5) {
      EXPECT_TRUE(q.entered);
    }
  // Events of the primary track: approached (from 7 m the side branches are hardly visible,
  // so the class is still open then), then entered, as a T-crossing.
  ASSERT_EQ(d.events.size(), 2u);
  EXPECT_EQ(d.events[0].kind, EventKind::kApproached);
  const auto entered = std::find_if(d.events.begin(), d.events.end(), [](const auto& e) { return e.kind == EventKind::kEntered; });
  ASSERT_NE(entered, d.events.end());
  EXPECT_EQ(entered->track_id, d.events[0].track_id);
  EXPECT_EQ(entered->gateway_class, kOutTCrossing);
  EXPECT_GT(d.scans_with_hypotheses, 50);
}

TEST(Tracking, CrossingTraversedThroughTheFront)
{
  DetectorOptions o;
  o.detect_narrow_passages = false;
  GatewayDetector det(o);
  const auto d = drive(det, test::crossing(kX, 2.0), -8.0, 3.5, 0.05);
  const auto trav = std::find_if(d.events.begin(), d.events.end(), [](const auto& e) { return e.kind == EventKind::kTraversed; });
  ASSERT_NE(trav, d.events.end());
  EXPECT_EQ(trav->gateway_class, kOutXCrossing);
  EXPECT_NEAR(trav->direction, 0.0, 1e-9);
}

// A crossing 6 m ahead seen on every scan but a run of `hidden` scans (a person walking through
// the view) while the robot drives 0.04 m per scan toward it.
std::vector<FinishedSequence> approach_with_gap(const TrackingOptions& o, int hidden, int64_t* tracks_created)
{
  GatewayTracker tracker(o);
  std::vector<FinishedSequence> out;
  int64_t max_id = 0;
  for (int k = 0; k < 140; ++k) {
    const double x = 0.04 * k;
    std::vector<CrossingDetection> dets;
    if (k < 40 || k >= 40 + hidden) {
      CrossingDetection d;
      d.points = {Vec2(5, 1), Vec2(7, 1), Vec2(7, -1), Vec2(5, -1)};
      d.axis = Vec2(1, 0);
      d.observation.distance = 6.0 - x;
      dets.push_back(d);
    }
    tracker.update(k + 1, geometry::Pose2(x, 0, 0), dets, {});
    for (const auto& t : tracker.tracks()) max_id = std::max(max_id, t.id);
    for (auto& f : tracker.take_finished()) out.push_back(std::move(f));
  }
  *tracks_created = max_id;
  return out;
}

TEST(Tracking, AShortOcclusionDoesNotSplitTheSequenceWhenLossNeedsTravel)
{
  TrackingOptions o;
  o.max_missed = 8;
  int64_t created = 0;
  // 15 hidden scans = 0.6 m of travel: counted in scans alone the track is lost and a new one
  // starts, leaving a corrupted first part and a complete sequence that starts late.
  o.lost_travel = 0.0;
  auto split = approach_with_gap(o, 15, &created);
  EXPECT_EQ(created, 2);
  ASSERT_EQ(split.size(), 2u);
  EXPECT_FALSE(split[0].entered);
  EXPECT_TRUE(split[1].entered);
  EXPECT_LT(split[1].sequence.front().distance, 4.5);
  // Lost only after 0.8 m without a sighting: one track, one complete sequence from 6 m.
  o.lost_travel = 0.8;
  auto whole = approach_with_gap(o, 15, &created);
  EXPECT_EQ(created, 1);
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_TRUE(whole[0].entered);
  EXPECT_NEAR(whole[0].sequence.front().distance, 6.0, 1e-9);
  // A longer gap (1.2 m) still loses it.
  whole = approach_with_gap(o, 30, &created);
  EXPECT_EQ(created, 2);
}

TEST(Tracking, AStandingRobotKeepsItsTracksOnlySoLong)
{
  TrackingOptions o;
  o.lost_travel = 0.5;
  o.max_missed_stationary = 40;
  GatewayTracker tracker(o);
  CrossingDetection d;
  d.points = {Vec2(5, 1), Vec2(7, 1), Vec2(7, -1), Vec2(5, -1)};
  d.axis = Vec2(1, 0);
  d.observation.distance = 6.0;
  tracker.update(1, geometry::Pose2(), {d}, {});
  for (int k = 2; k <= 40; ++k) tracker.update(k, geometry::Pose2(), {}, {});
  EXPECT_EQ(tracker.take_finished().size(), 0u);
  for (int k = 41; k <= 45; ++k) tracker.update(k, geometry::Pose2(), {}, {});
  const auto f = tracker.take_finished();
  ASSERT_EQ(f.size(), 1u);
  EXPECT_FALSE(f[0].entered);
}

TEST(DoorConfirmation, RectangleEdgesMakeAPassageADoor)
{
  DetectorOptions o;
  o.detect_crossings = false;
  GatewayDetector det(o);
  // A door frame 0.9 x 2.1 m in the wall x = 2, facing the robot (normal -x).
  Rectangle3 r;
  r.corners = {Eigen::Vector3d(2, -0.45, 0), Eigen::Vector3d(2, 0.45, 0), Eigen::Vector3d(2, 0.45, 2.1), Eigen::Vector3d(2, -0.45, 2.1)};
  r.normal = {-1, 0, 0};
  r.width = 0.9;
  r.height = 2.1;
  const auto edges = door_edges(r, o.doors);
  ASSERT_TRUE(edges);
  EXPECT_TRUE(edges_match(*edges, {2, 0.45}, {2, -0.45}, 0.05));
  // A whiteboard-sized or a lying rectangle is not a door.
  Rectangle3 small = r;
  small.width = 0.3;
  EXPECT_FALSE(door_edges(small, o.doors));
  Rectangle3 flat = r;
  flat.normal = {0, 0, 1};
  EXPECT_FALSE(door_edges(flat, o.doors));

  det.add_rectangles(0, geometry::Pose2(), {r});
  const auto d = drive(det, test::door(2.0, 0.9), -1.0, 0.5, 0.02);
  ASSERT_FALSE(d.events.empty());
  EXPECT_EQ(d.events[0].gateway_class, kOutDoor);
}

}  // namespace
}  // namespace rgnav::gateway_detector
