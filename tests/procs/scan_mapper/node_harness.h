// A scan mapper node on the FakeBus, and the corridor drive the node tests feed it.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "bus/typed.h"
#include "fake_bus_node.h"
#include "scan_mapper/scan_mapper_conversions.h"
#include "scan_mapper/scan_mapper_node.h"
#include "synthetic_world.h"

namespace rgnav::scan_mapper::testing {

inline ScanMapperOptions node_test_options()
{
  ScanMapperOptions o;
  o.base_from_laser = Pose2{};
  return o;
}

struct NodeHarness : rgnav::testing::FakeBusNode
{
  explicit NodeHarness(const PersistenceOptions& p, const ScanMapperOptions& o = node_test_options())
      : FakeBusNode("scan_mapper_test")
  {
    adapter = std::make_unique<ScanMapperNode>(*node, o, ScanMapperChannels{}, p);
  }
  template <class T>
  std::vector<T> published(const std::string& channel) const
  {
    return rgnav::testing::decoded<T>(*bus, channel);
  }
  // Lets a running pose graph optimisation finish and be adopted (it runs on a worker thread).
  void settle()
  {
    while (adapter->optimization_running()) node->spin_once(std::chrono::milliseconds(50));
  }
  // Sends bytes as they are, past the publisher's checks (a hostile or broken sender).
  template <class T>
  void send_raw(const std::string& channel, const T& msg)
  {
    std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
    ASSERT_GE(msg.encode(buf.data(), 0, static_cast<int>(buf.size())), 0);
    bus->publish(channel, buf.data(), buf.size());
  }
  std::unique_ptr<ScanMapperNode> adapter;
};

// True pose at step i of the drive: out along the corridor and back, 0.05 m steps, through
// the doorway in the wall at x = 3 (driving through the wall itself would show the mapper one
// zero-thickness wall from both sides, which oriented normals rightly keep apart).
inline Pose2 drive_truth(int i)
{
  const int leg = i % 300;
  const double s = leg < 150 ? leg * 0.05 : (300 - leg) * 0.05;
  return leg < 150 ? Pose2{1 + s, 4.5, 0} : Pose2{1 + s, 4.5, M_PI};
}

inline odometry_t drive_odometry(int i, int64_t seq0 = 0)
{
  const Pose2 truth = drive_truth(i);
  odometry_t o{};
  o.utime = 1'000'000 + i * 100'000;
  o.seq = seq0 + i + 1;
  o.odom_from_base = msg::to_msg(Pose2{truth.x() * 1.01, truth.y(), truth.theta()});
  return o;
}

inline laser_scan_t drive_scan(int i, int64_t id0 = 0)
{
  static const auto world = office_world();
  std::mt19937 rng(static_cast<unsigned>(2 + i));
  LaserModel m;
  m.noise_m = 0.01;
  auto scan = cast_scan(world, drive_truth(i), m, &rng, id0 + i + 1, 1'000'000 + i * 100'000);
  scan.sensor = "laser_front";
  return msg::to_msg(scan);
}

// Steps [from, to): odometry then a scan each; `settle` waits for optimisations after each.
inline void drive(NodeHarness& h, int from, int to, int64_t seq0 = 0, int64_t id0 = 0, bool settle = true)
{
  for (int i = from; i < to; ++i) {
    bus::publish(h.node->bus(), "ODOMETRY", drive_odometry(i, seq0));
    bus::publish(h.node->bus(), "LASER_FRONT", drive_scan(i, id0));
    if (settle) h.settle();
  }
}

}  // namespace rgnav::scan_mapper::testing
