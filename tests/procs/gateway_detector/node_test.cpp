#include <gtest/gtest.h>

#include "fake_bus_node.h"
#include "gateway_detector/gateway_conversions.h"
#include "gateway_detector/gateway_detector_node.h"
#include "msg/conversions.h"
#include "synthetic.h"

namespace rgnav::gateway_detector {
namespace {

laser_scan_t laser_msg(sensors::LaserScan s)
{
  s.sensor = "laser_front";
  return msg::to_msg(s);
}

struct Fixture : rgnav::testing::FakeBusNode
{
  explicit Fixture(const std::string& input) : FakeBusNode("gateway_detector_test")
  {
    NodeChannels ch;
    ch.input = input;
    DetectorOptions o;
    adapter = std::make_unique<GatewayDetectorNode>(*node, GatewayDetector(o), ch, geometry::Pose2(0.12, 0, 0));
  }
  template <class T>
  std::vector<T> decoded(const std::string& channel) const
  {
    return rgnav::testing::decoded<T>(*bus, channel);
  }
  std::unique_ptr<GatewayDetectorNode> adapter;
};

TEST(GatewayDetectorNode, LaserAndOdometryThroughADoor)
{
  Fixture f("laser");
  const auto walls = test::door(2.0, 0.9);
  int64_t id = 1;
  for (double x = -1.0; x <= 3.5; x += 0.02, ++id) {
    const int64_t t = 1'000'000 + id * 13333;
    const geometry::Pose2 base(x, 0, 0);
    odometry_t odo{};
    odo.utime = t;
    odo.seq = id;
    odo.odom_from_base = msg::to_msg(base);
    odo.status = odometry_t::STATUS_SIMULATED;
    ASSERT_TRUE(bus::publish(*f.bus, "ODOMETRY", odo));
    sensors::LaserScan s = test::cast(walls, base * geometry::Pose2(0.12, 0, 0), 0.005, static_cast<unsigned>(id));
    s.utime = t;
    s.scan_id = id;
    ASSERT_TRUE(bus::publish(*f.bus, "LASER_FRONT", laser_msg(s)));
  }
  // A broken scan is dropped by the typed bus and changes nothing.
  laser_scan_t bad = laser_msg(test::cast(walls, geometry::Pose2()));
  bad.scan_id = id;
  bad.ranges[3] = -1.f;
  std::vector<uint8_t> raw(static_cast<size_t>(bad.getEncodedSize()));
  bad.encode(raw.data(), 0, static_cast<int>(raw.size()));
  f.bus->publish("LASER_FRONT", raw.data(), raw.size());

  const auto hyps = f.decoded<gateway_hypotheses_t>("GATEWAY_HYPOTHESES");
  EXPECT_EQ(static_cast<int64_t>(hyps.size()), id - 1);  // one message per good scan
  EXPECT_EQ(f.adapter->scans_processed(), id - 1);
  bool saw_door = false;
  for (const auto& h : hyps)
    for (const auto& g : h.hypotheses)
      if (g.gateway_class == gateway_hypothesis_t::CLASS_NARROW_PASSAGE) {
        saw_door = true;
        EXPECT_EQ(g.npoints, 2);
        EXPECT_NEAR(g.class_probability[gateway_hypothesis_t::CLASS_NARROW_PASSAGE], 1.f, 1e-6);
        // Gateway points in the base frame of that scan: x = 2 - robot x.
        EXPECT_NEAR(g.gateway_points[0].x + h.map_from_base.x, 2.0, 0.06);
      }
  EXPECT_TRUE(saw_door);
  const auto events = f.decoded<gateway_event_t>("GATEWAY_EVENTS");
  std::vector<int8_t> kinds;
  for (const auto& e : events)
    if (e.gateway_class == gateway_hypothesis_t::CLASS_NARROW_PASSAGE) kinds.push_back(e.event);
  EXPECT_EQ(kinds, (std::vector<int8_t>{gateway_event_t::EVENT_APPROACHED, gateway_event_t::EVENT_ENTERED,
                                        gateway_event_t::EVENT_TRAVERSED}));
  EXPECT_GT(f.node->drops().total(), 0);
}

TEST(GatewayDetectorNode, AlignedScansCarryTheirPose)
{
  Fixture f("aligned");
  const auto walls = test::crossing(kT, 2.0);
  int64_t id = 1;
  for (double x = -8.0; x <= -1.0; x += 0.05, ++id) {
    aligned_scan_t a{};
    a.utime = 1'000'000 + id * 13333;
    a.scan_id = id;
    a.map_from_base = msg::to_msg(geometry::Pose2(x, 0, 0));
    a.odom_from_base = msg::to_msg(geometry::Pose2(x + 0.3, -0.1, 0.02));  // drifted odometry
    a.base_from_laser = msg::to_msg(geometry::Pose2(0.12, 0, 0));
    sensors::LaserScan s = test::cast(walls, geometry::Pose2(x + 0.12, 0, 0), 0.005, static_cast<unsigned>(id));
    s.utime = a.utime;
    s.scan_id = id;
    a.scan = laser_msg(s);
    ASSERT_TRUE(bus::publish(*f.bus, "ALIGNED_SCAN", a));
    if (id == 3) {  // a correction of an old scan is not a new observation
      a.revision = 1;
      ASSERT_TRUE(bus::publish(*f.bus, "ALIGNED_SCAN", a));
    }
  }
  const auto hyps = f.decoded<gateway_hypotheses_t>("GATEWAY_HYPOTHESES");
  ASSERT_EQ(static_cast<int64_t>(hyps.size()), id - 1);
  const auto& last = hyps.back();
  ASSERT_GE(last.nhypotheses, 1);
  const auto& g = last.hypotheses[0];
  EXPECT_EQ(g.gateway_class, gateway_hypothesis_t::CLASS_T_CROSSING);
  EXPECT_EQ(g.npoints, 4);
  // T-crossing: the entry and both sides are open, the front is not.
  EXPECT_EQ(g.ncrossing_points, 3);
  EXPECT_EQ(g.ndirections, 3);
  float sum = 0;
  for (float p : g.class_probability) sum += p;
  EXPECT_NEAR(sum, 1.f, 1e-5);
  EXPECT_GT(g.observations, 10);
}

// The scan round trip is tested with the conversion, in tests/common/msg_conversions_test.cpp.
TEST(GatewayConversions, ClassMapping)
{
  for (int c = 0; c < kNumOutputClasses; ++c) EXPECT_EQ(from_class_msg(to_class_msg(c)), c);
  EXPECT_EQ(to_class_msg(kOutLTurn), gateway_hypothesis_t::CLASS_L_TURN);
  EXPECT_EQ(to_class_msg(kOutDoor), gateway_hypothesis_t::CLASS_DOOR);
}

}  // namespace
}  // namespace rgnav::gateway_detector
