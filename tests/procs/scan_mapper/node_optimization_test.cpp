// The pose graph optimisation after a loop closure runs on a worker thread: while it runs
// (here held until the test lets it go, so nothing depends on timing) the node keeps
// heartbeating and taking scans; its result is then adopted on the node thread, the scans
// added meanwhile are moved with the map, and the corrections are republished.
#include <gtest/gtest.h>

#include <future>

#include "node_harness.h"

namespace sm = rgnav::scan_mapper;
using rgnav::aligned_scan_t;
using sm::testing::drive;
using sm::testing::drive_truth;
using sm::testing::NodeHarness;

TEST(ScanMapperNodeOptimization, NodeKeepsServicingWhileAnOptimisationRuns)
{
  NodeHarness h(sm::PersistenceOptions{});
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<int> running{0};
  h.adapter->set_optimization_runner([released, &running](sm::OptimizationJob& job) {
    running = 1;
    released.wait();  // a deliberately slow optimisation: as slow as the test wants
    job.run();
  });
  // Out along the corridor and back until a loop closure starts an optimisation.
  int i = 0;
  for (; i < 300 && h.adapter->optimizations_started() == 0; ++i) drive(h, i, i + 1, 0, 0, false);
  ASSERT_EQ(h.adapter->optimizations_started(), 1) << "no loop closure on the way back";
  ASSERT_TRUE(h.adapter->optimization_running());

  // Meanwhile: heartbeats go out and scans are mapped and published.
  const auto beats0 = h.node->heartbeat_seq();
  const size_t aligned0 = h.published<aligned_scan_t>("ALIGNED_SCAN").size();
  const size_t nodes0 = h.adapter->mapper().nodes().size();
  const int first_during = i;
  for (int k = 0; k < 20; ++k, ++i) {
    drive(h, i, i + 1, 0, 0, false);
    h.node->spin_once(std::chrono::milliseconds(20));
  }
  for (int k = 0; k < 500 && h.node->heartbeat_seq() < beats0 + 2; ++k) h.node->spin_once(std::chrono::milliseconds(50));
  EXPECT_GE(h.node->heartbeat_seq(), beats0 + 2);
  EXPECT_GT(h.published<aligned_scan_t>("ALIGNED_SCAN").size(), aligned0 + 3);
  EXPECT_GT(h.adapter->mapper().nodes().size(), nodes0 + 3);
  EXPECT_TRUE(h.adapter->optimization_running());  // still held: all of the above happened during it
  EXPECT_EQ(running.load(), 1);
  EXPECT_EQ(h.adapter->optimizations_applied(), 0);

  release.set_value();
  h.settle();
  EXPECT_EQ(h.adapter->optimizations_applied(), 1);
  int republished = 0;
  for (const auto& a : h.published<aligned_scan_t>("ALIGNED_SCAN")) republished += a.revision > 0;
  EXPECT_GT(republished, 0);
  // Scans mapped during the optimisation were moved with the map: still where they truly are.
  for (const auto& n : h.adapter->mapper().nodes()) {
    const int step = static_cast<int>(n.scan.scan_id) - 1;
    if (step < first_during) continue;
    const sm::Pose2 t = drive_truth(step);
    EXPECT_LT(std::hypot(n.map_from_base.x() - t.x(), n.map_from_base.y() - t.y()), 0.2) << step;
  }
}
