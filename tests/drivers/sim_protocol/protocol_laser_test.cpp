// Protocol mode's laser: the ScanSource the LMS 2xx emulator asks for ranges. Without noise
// it must reproduce the simulator's own ray caster (Lms2xxModel::true_ranges) beam for beam;
// it serves any LMS variant; and it answers from the scene state recorded nearest the time
// of the requested scan.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/lms2xx_model.h"
#include "sim/protocol_laser.h"
#include "sim/world_yaml.h"

namespace rgnav::sim {
namespace {

World office() { return load_world(std::string(RGNAV_SOURCE_DIR) + "/config/worlds/office.yaml"); }

LaserSceneState state_of(const World& w, int64_t utime, const Pose2& pose)
{
  LaserSceneState s;
  s.utime = utime;
  s.world_from_base = pose;
  for (const auto& d : w.doors) s.door_open.push_back(d.open_at(0.0) ? 1 : 0);
  for (const auto& p : w.people) s.people.push_back({p.path.front(), p.radius});
  return s;
}

drivers::sick::ScanRequest request(int64_t utime, double range_deg, double res_deg)
{
  drivers::sick::ScanRequest r;
  r.utime = utime;
  r.angle_min_rad = -range_deg * M_PI / 360.0;
  r.angle_increment_rad = res_deg * M_PI / 180.0;
  r.count = static_cast<int>(std::lround(range_deg / res_deg)) + 1;
  return r;
}

TEST(ProtocolLaser, ServesTheSimulatorsRayCastForEveryVariant)
{
  const World w = office();
  const Scene scene(w);
  Lms2xxOptions laser;
  laser.noise_sigma = 0.0;
  SimScanSource source(scene, laser, Rng(1));
  const LaserSceneState s = state_of(w, 1000, w.start);
  source.record(s);

  for (int beams : {181, 361}) {
    Lms2xxOptions o = laser;
    o.beams = beams;
    o.range_mode_m = 80;
    const Lms2xxModel model(o, Rng(1));
    const auto expected = model.true_ranges(scene, s.door_open, s.people, model.laser_pose(s.world_from_base));
    const auto got = source.ranges(request(1000, 180.0, beams == 181 ? 1.0 : 0.5));
    ASSERT_EQ(got.size(), expected.size());
    int hits = 0;
    for (size_t i = 0; i < got.size(); ++i) {
      if (!std::isfinite(expected[i])) {
        EXPECT_FALSE(std::isfinite(got[i])) << "beam " << i;
        continue;
      }
      ++hits;
      EXPECT_NEAR(got[i], expected[i], 1e-5) << "beam " << i;
    }
    EXPECT_GT(hits, beams / 2) << "the office around the start pose is mostly within reach";
  }
  // The 100 deg variant at 0.25 deg: every other beam is one of the 180 deg scan at 0.5 deg
  // (from -50 deg: index 80 there).
  const auto narrow = source.ranges(request(1000, 100.0, 0.25));
  const auto wide = source.ranges(request(1000, 180.0, 0.5));
  ASSERT_EQ(narrow.size(), 401u);
  for (size_t i = 0; i < narrow.size(); i += 2) EXPECT_NEAR(narrow[i], wide[80 + i / 2], 1e-5) << "beam " << i;
}

TEST(ProtocolLaser, AnswersFromTheStateNearestTheScanTime)
{
  const World w = office();
  const Scene scene(w);
  Lms2xxOptions laser;
  laser.noise_sigma = 0.0;
  SimScanSource source(scene, laser, Rng(1), std::chrono::milliseconds(100));
  Pose2 p = w.start;
  for (int k = 0; k <= 300; ++k) {  // 1 ms steps, moving 1 mm per step along +y
    p.y = w.start.y + 0.001 * k;
    source.record(state_of(w, 1'000'000 + 1000 * k, p));
  }
  EXPECT_NEAR(source.state_at(1'250'400).world_from_base.y, w.start.y + 0.250, 1e-12);
  EXPECT_NEAR(source.state_at(1'250'600).world_from_base.y, w.start.y + 0.251, 1e-12);
  // After the newest state: the newest; before the 100 ms history: the oldest kept.
  EXPECT_NEAR(source.state_at(2'000'000).world_from_base.y, w.start.y + 0.300, 1e-12);
  const double oldest = source.state_at(0).world_from_base.y - w.start.y;
  EXPECT_GE(oldest, 0.199 - 1e-9);
  EXPECT_LE(oldest, 0.200 + 1e-9);

  // The forward beam sees the robot 0.1 m closer to what lies ahead 100 ms later.
  const auto r0 = source.ranges(request(1'200'000, 180.0, 1.0));
  const auto r1 = source.ranges(request(1'300'000, 180.0, 1.0));
  ASSERT_TRUE(std::isfinite(r0[90]));
  EXPECT_NEAR(r0[90] - r1[90], 0.1, 1e-5);
}

TEST(ProtocolLaser, AddsTheConfiguredNoise)
{
  const World w = office();
  const Scene scene(w);
  Lms2xxOptions laser;
  laser.noise_sigma = 0.02;
  SimScanSource noisy(scene, laser, Rng(7));
  laser.noise_sigma = 0.0;
  SimScanSource exact(scene, laser, Rng(7));
  const auto s = state_of(w, 5, w.start);
  noisy.record(s);
  exact.record(s);
  double sum2 = 0.0;
  int n = 0;
  for (int k = 0; k < 20; ++k) {
    const auto a = noisy.ranges(request(5, 180.0, 1.0));
    const auto b = exact.ranges(request(5, 180.0, 1.0));
    for (size_t i = 0; i < a.size(); ++i)
      if (std::isfinite(b[i])) {
        sum2 += (a[i] - b[i]) * (a[i] - b[i]);
        ++n;
      }
  }
  ASSERT_GT(n, 1000);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.02, 0.002);
  EXPECT_EQ(noisy.scans_served(), 20u);
}

}  // namespace
}  // namespace rgnav::sim
