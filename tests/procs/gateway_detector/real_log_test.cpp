// Sanity of narrow-passage detection on real data: the Intel Research Lab log with its
// corrected poses (diss. table 6.1 counts 8 doors traversed there).
#include <gtest/gtest.h>

#include <filesystem>

#include "gateway_detector/gateway_detector.h"
#include "importers/carmen_parser.h"

namespace rgnav::gateway_detector {
namespace {

const char* const kIntel = RGNAV_SHARED_DATA "/laser/corrected/intel-corrected.log.gz";

TEST(RealLog, IntelDoorsAreTraversedAndPassagesHaveDoorWidths)
{
  if (!std::filesystem::exists(kIntel)) GTEST_SKIP() << kIntel << " not present";
  importers::CarmenOptions co;
  co.flaser_pose_is_reference = true;
  const auto log = importers::read_carmen(kIntel, co);
  ASSERT_EQ(log.scans.size(), log.reference.size());
  ASSERT_GT(log.scans.size(), 800u);

  // The log keeps one scan per ~0.55 m of travel: a door within D_NP^max is seen in only a
  // few scans, so one observation must do to report it.
  DetectorOptions options;
  options.tracking.min_observations = 1;
  options.tracking.max_missed = 2;
  options.tracking.passage_match_distance = 0.4;
  GatewayDetector det(options);
  int passages = 0, traversed = 0, crossings_seen = 0;
  std::vector<Vec2> doors;
  for (size_t i = 0; i < log.scans.size(); ++i) {
    const auto& r = log.scans[i];
    PosedScan ps;
    ps.scan = r;
    ps.scan.scan_id = static_cast<int64_t>(i + 1);
    const auto& p = log.reference[i];
    ps.map_from_base = geometry::Pose2(p.x, p.y, p.theta);
    for (const auto& np : detect_narrow_passages(ps.scan, det.options().narrow_passages)) {
      ++passages;
      EXPECT_GE(np.width, det.options().narrow_passages.min_width);
      EXPECT_LE(np.width, det.options().narrow_passages.max_width);
      EXPECT_LT(np.distance, det.options().narrow_passages.max_distance);
    }
    const auto out = det.process(ps);
    for (const auto& h : out.hypotheses) crossings_seen += h.gateway_class >= kOutXCrossing;
    for (const auto& e : out.events) {
      if (e.kind != EventKind::kTraversed || e.gateway_class != kOutNarrowPassage) continue;
      ++traversed;
      const Vec2 mid = 0.5 * (e.gateway_points[0] + e.gateway_points[1]);
      if (std::none_of(doors.begin(), doors.end(), [&](const Vec2& d) { return (d - mid).norm() < 1.0; })) doors.push_back(mid);
    }
  }
  RecordProperty("passages", passages);
  RecordProperty("traversed", traversed);
  RecordProperty("distinct_doors", static_cast<int>(doors.size()));
  std::cout << "intel: " << passages << " narrow passages, " << traversed << " traversals of "
            << doors.size() << " distinct passages, " << crossings_seen << " crossing hypotheses\n";
  // The robot goes through several of the lab's doors (8 in the dissertation's run).
  EXPECT_GE(doors.size(), 4u);
  EXPECT_LE(doors.size(), 40u);
}

}  // namespace
}  // namespace rgnav::gateway_detector
