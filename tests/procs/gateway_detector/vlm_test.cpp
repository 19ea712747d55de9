#include <gtest/gtest.h>

#include "gateway_detector/classifiers.h"
#include "gateway_detector/gateway_detector.h"
#include "synthetic.h"

namespace rgnav::gateway_detector {
namespace {

using test::cast;
using test::crossing;

DetectorOptions options_for(double w)
{
  DetectorOptions o;
  o.vlm.hallway_width = w;
  o.measures.hallway_width = w;
  return o;
}

// The VLM hypothesis nearest to the true crossing square, if any is within `tol` everywhere.
const std::pair<Vlm, Observation>* true_hypothesis(const std::vector<std::pair<Vlm, Observation>>& hs, double x0,
                                                   double w, double tol)
{
  const Vec2 truth[4] = {{x0, w / 2}, {x0 + w, w / 2}, {x0 + w, -w / 2}, {x0, -w / 2}};
  const std::pair<Vlm, Observation>* best = nullptr;
  double best_err = tol;
  for (const auto& h : hs) {
    double err = 0;
    for (int k = 0; k < 4; ++k) err = std::max(err, (h.first.points[static_cast<size_t>(k)] - truth[k]).norm());
    if (err < best_err) {
      best_err = err;
      best = &h;
    }
  }
  return best;
}

class VlmGrouping : public ::testing::TestWithParam<std::tuple<int, double>>
{
};

TEST_P(VlmGrouping, FindsTheCrossingAndItsClass)
{
  const auto [cls, w] = GetParam();
  const GatewayDetector det(options_for(w));
  for (double dist : {4.0, 2.5}) {
    const sensors::LaserScan s = cast(crossing(cls, w), geometry::Pose2(-dist, 0.0, 0.0), 0.005, 7);
    const auto hs = det.observe_crossings(s);
    const auto* h = true_hypothesis(hs, dist, w, 0.25);
    ASSERT_NE(h, nullptr) << crossing_class_name(cls) << " at " << dist << " m: " << hs.size() << " hypotheses";
    EXPECT_EQ(soc(h->second.weights), cls) << crossing_class_name(cls) << " at " << dist << " m";
    EXPECT_NEAR(h->second.distance, std::hypot(dist + w / 2, 0.0), 0.3);
  }
}

INSTANTIATE_TEST_SUITE_P(AllClasses, VlmGrouping,
                         ::testing::Combine(::testing::Values(int{kX}, int{kT}, int{kLT}, int{kRT}, int{kLTurn},
                                                              int{kRTurn}, int{kDeadEnd}),
                                            ::testing::Values(2.0, 3.0)));

TEST(VlmGrouping, HiddenLineFromSingularityAndFromPrior)
{
  // L-turn: the left wall ends in a depth singularity, which places the hidden line; a dead
  // end has none, so its hidden line comes from the hallway width alone.
  const GatewayDetector det(options_for(2.0));
  ScanFeatures f = extract_features(cast(crossing(kLTurn, 2.0), geometry::Pose2(-3, 0, 0)), FeatureOptions{});
  auto vlms = group_vlms(f, det.options().vlm);
  EXPECT_TRUE(std::any_of(vlms.begin(), vlms.end(), [](const Vlm& v) { return v.hidden_from_singularity; }));
  f = extract_features(cast(crossing(kDeadEnd, 2.0), geometry::Pose2(-3, 0, 0)), FeatureOptions{});
  vlms = group_vlms(f, det.options().vlm);
  ASSERT_FALSE(vlms.empty());
  EXPECT_TRUE(std::none_of(vlms.begin(), vlms.end(), [](const Vlm& v) { return v.hidden_from_singularity; }));
}

TEST(VlmGrouping, PlainHallwayHasNoFrontLine)
{
  const GatewayDetector det(options_for(2.0));
  const sensors::LaserScan s = cast({{{-10, 1}, {30, 1}}, {{-10, -1}, {30, -1}}}, geometry::Pose2());
  EXPECT_TRUE(det.observe_crossings(s).empty());
}

TEST(VlmGrouping, DuplicatesAreRemoved)
{
  const GatewayDetector det(options_for(2.0));
  const auto hs = det.observe_crossings(cast(crossing(kX, 2.0), geometry::Pose2(-3, 0, 0)));
  for (size_t i = 0; i < hs.size(); ++i)
    for (size_t j = i + 1; j < hs.size(); ++j) {
      double worst = 0;
      for (int k = 0; k < 4; ++k) worst = std::max(worst, (hs[i].first.points[k] - hs[j].first.points[k]).norm());
      EXPECT_GT(worst, det.options().vlm.duplicate_distance);
    }
}

}  // namespace
}  // namespace rgnav::gateway_detector
