// Loop-closure verification: uncertainty along the graph (Dijkstra over drift variances) and
// pairwise consistency of closure hypotheses.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "scan_mapper/loop_search.h"

namespace sm = rgnav::scan_mapper;

namespace {

// A straight chain of n nodes 1 m apart along x.
sm::PoseGraph chain(int n)
{
  sm::PoseGraph g;
  for (int i = 0; i < n; ++i) g.add_node(sm::Pose2{static_cast<double>(i), 0.0, 0.0});
  for (int i = 0; i + 1 < n; ++i) g.add_edge({i, i + 1, sm::Pose2{1.0, 0.0, 0.0}, Eigen::Matrix3d::Identity() * 1e4, false});
  return g;
}

}  // namespace

TEST(LoopSearch, UncertaintyGrowsAlongTheChainAndShrinksAcrossAClosure)
{
  sm::DriftModel drift;
  auto g = chain(50);
  auto u = sm::relative_uncertainty(g, 49, drift);
  ASSERT_TRUE(u[0].reached());
  EXPECT_NEAR(u[0].length_m, 49.0, 1e-9);
  EXPECT_GT(u[0].sigma_xy(), u[40].sigma_xy());
  EXPECT_GT(u[40].sigma_xy(), 0.0);
  // A closure 49 -> 0 with 2 cm / 0.5 deg uncertainty: node 0 is now close to node 49.
  Eigen::Matrix3d cov = Eigen::Vector3d(4e-4, 4e-4, 7.6e-5).asDiagonal();
  g.add_edge({0, 49, sm::Pose2{49.0, 0.0, 0.0}, cov.inverse(), true});
  const auto v = sm::relative_uncertainty(g, 49, drift);
  EXPECT_LT(v[0].sigma_xy(), 0.2 * u[0].sigma_xy());
  EXPECT_LT(v[1].sigma_xy(), u[1].sigma_xy());
}

TEST(LoopSearch, PairwiseConsistencySeparatesAgreeingFromLookAlikeClosures)
{
  // Truth: nodes along x; the estimate of the newest nodes drifted by 0.5 m in y (what a
  // closure corrects), the same for both, so the chain between them is accurate.
  sm::PoseGraph g;
  for (int i = 0; i < 40; ++i) g.add_node(sm::Pose2{0.2 * i, i >= 30 ? 0.5 : 0.0, 0.0});
  const sm::ConsistencyTolerance tol{0.2, 0.05};
  // True closures: node 30 seen from 0, node 35 seen from 5 (0.2 m per index, drift-free).
  const sm::ClosureHypothesis a{30, 0, sm::Pose2{6.0, 0.0, 0.0}};
  const sm::ClosureHypothesis b{35, 5, sm::Pose2{6.0, 0.0, 0.0}};
  EXPECT_TRUE(sm::pairwise_consistent(g, a, b, tol));
  // A look-alike match puts node 35 1 m further along than the chain allows.
  const sm::ClosureHypothesis wrong{35, 5, sm::Pose2{7.0, 0.0, 0.0}};
  EXPECT_FALSE(sm::pairwise_consistent(g, a, wrong, tol));
  // ... or turned by 10 degrees.
  const sm::ClosureHypothesis turned{35, 5, sm::Pose2{6.0, 0.0, 0.17}};
  EXPECT_FALSE(sm::pairwise_consistent(g, a, turned, tol));
}

TEST(LoopSearch, TheNextScansMatchIsNoWitness)
{
  // Two hypotheses that agree: node 31's match repeats node 30's (0.2 m on, the same anchor, the
  // same error), node 36's comes from a view 1.2 m further on. The first pair is one look at the
  // place counted twice: were the match a look-alike's, the next scan would fit it as well.
  sm::PoseGraph g;
  for (int i = 0; i < 40; ++i) g.add_node(sm::Pose2{0.2 * i, i >= 30 ? 0.5 : 0.0, 0.0});
  const sm::ConsistencyTolerance tol{0.2, 0.05};
  const sm::ClosureHypothesis a{30, 0, sm::Pose2{6.0, 0.0, 0.0}, Eigen::Matrix3d::Identity(), false, 6.0};
  const sm::ClosureHypothesis next{31, 0, sm::Pose2{6.2, 0.0, 0.0}, Eigen::Matrix3d::Identity(), false, 6.2};
  const sm::ClosureHypothesis later{36, 5, sm::Pose2{6.2, 0.0, 0.0}, Eigen::Matrix3d::Identity(), false, 7.2};
  ASSERT_TRUE(sm::pairwise_consistent(g, a, next, tol));
  ASSERT_TRUE(sm::pairwise_consistent(g, a, later, tol));
  EXPECT_FALSE(sm::witnesses(g, a, next, tol, 1.0));
  EXPECT_TRUE(sm::witnesses(g, a, later, tol, 1.0));
  // The order they were found in does not matter, and agreement is still needed.
  EXPECT_TRUE(sm::witnesses(g, later, a, tol, 1.0));
  const sm::ClosureHypothesis wrong{36, 5, sm::Pose2{7.2, 0.0, 0.0}, Eigen::Matrix3d::Identity(), false, 7.2};
  EXPECT_FALSE(sm::witnesses(g, a, wrong, tol, 1.0));
  // Switched off (0 m), the next scan's match confirms the first, as before the rule.
  EXPECT_TRUE(sm::witnesses(g, a, next, tol, 0.0));
}
