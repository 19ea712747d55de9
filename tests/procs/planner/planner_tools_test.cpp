// ./rgnav goto and ./rgnav name-region against a real planner process on real udpm, in a private
// network namespace: the test plays the localizer (POSE on the two-room map). goto follows its
// goal to the end (exit 0), says no path (exit 4, the goal cancelled), is cancelled by Ctrl-C
// (exit 3, the planner confirms CANCELLED); a name given with name-region is a goal at once.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <thread>

#include "bus/typed.h"
#include "bus_watch.h"
#include "child_process.h"
#include "msg/conversions.h"
#include "rgnav/global_path_t.hpp"
#include "rgnav/region_pose_t.hpp"
#include "time/message_time.h"
#include "two_room_map.h"

namespace rgnav::testing {
namespace {

using namespace std::chrono_literals;
using geometry::Pose2;

struct Stack
{
  TempDir dir{"planner_tools"};
  TwoRoomWorld world = two_room_world();
  bus::LcmBus bus{test_udpm_url()};
  bus::DropCounter drops;
  std::vector<global_path_t> paths;
  std::optional<ChildProcess> planner;

  Stack()
  {
    write_rgmap_json(world.map, dir.file("map"));
    bus::subscribe<global_path_t>(
        bus, "GLOBAL_PATH", [this](const global_path_t& m, const bus::RawMessage&) { paths.push_back(m); }, &drops);
    ChildOptions o;
    o.stderr_path = dir.file("planner.stderr");
    planner.emplace(std::vector<std::string>{RGNAV_PLANNER_BIN, "--lcm-url", test_udpm_url(), "--map", dir.file("map"),
                                             "--state-file", dir.file("planner.json")},
                    o);
    HeartbeatWatch hb(test_udpm_url());
    EXPECT_TRUE(hb.wait_for("planner", 20s, planner->pid())) << read_file(dir.file("planner.stderr"));
  }

  // The localizer's estimate, now, in the room holding `map_from_base`.
  void pose(const Pose2& map_from_base)
  {
    const int64_t region = map_from_base.x() < 4.0 ? world.room_a : world.room_b;
    region_pose_t m{};
    m.utime = time::wall_utime();
    m.scan_id = 1;
    m.region_id = region;
    m.region_from_base = msg::to_msg(world.map.region(region)->map_from_region.inverse() * map_from_base);
    m.map_from_base = msg::to_msg(map_from_base);
    m.odom_from_base = msg::to_msg(map_from_base);
    m.confidence = 0.9f;
    ASSERT_TRUE(bus::publish(bus, "POSE", m));
  }

  // Pumps the bus for `d`, publishing the pose every 200 ms.
  void hold(const Pose2& at, std::chrono::milliseconds d)
  {
    const auto until = std::chrono::steady_clock::now() + d;
    while (std::chrono::steady_clock::now() < until) {
      pose(at);
      bus.handle(200ms);
    }
  }

  ChildProcess go(std::vector<std::string> args, const std::string& log)
  {
    args.insert(args.begin(), RGNAV_GOTO_BIN);
    args.insert(args.end(), {"--lcm-url", test_udpm_url()});
    ChildOptions o;
    o.stdout_path = dir.file(log);
    return ChildProcess(args, o);
  }

  // Pumps (keeping the pose alive) until the child ends; its exit status.
  std::optional<ExitStatus> finish(ChildProcess& c, const Pose2& at, std::chrono::milliseconds timeout)
  {
    const auto until = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < until) {
      hold(at, 200ms);
      if (auto s = c.wait_for(0ms)) return s;
    }
    return std::nullopt;
  }
};

TEST(PlannerTools, GotoFollowsItsGoalToTheEnd)
{
  RGNAV_REQUIRE_NETNS();
  Stack s;
  s.hold(Pose2(1.0, 1.5, 0.0), 500ms);
  auto go = s.go({"room_b", "2.5", "1.0", "0", "--goal-id", "31"}, "goto.out");
  // On the way: the planner has it (GLOBAL_PATH OK through the door).
  s.hold(Pose2(1.0, 1.5, 0.0), 2000ms);
  ASSERT_TRUE(go.running()) << read_file(s.dir.file("goto.out"));
  ASSERT_FALSE(s.paths.empty());
  EXPECT_EQ(s.paths.back().goal_id, 31);
  EXPECT_EQ(s.paths.back().status, global_path_t::STATUS_OK) << s.paths.back().reason;
  // The robot is there: reached, goto exits 0.
  const auto status = s.finish(go, Pose2(6.5, 1.0, 0.0), 10s);
  ASSERT_TRUE(status.has_value()) << read_file(s.dir.file("goto.out"));
  EXPECT_TRUE(status->clean()) << status->describe() << "\n" << read_file(s.dir.file("goto.out"));
  const std::string out = read_file(s.dir.file("goto.out"));
  EXPECT_NE(out.find("on the way: regions 1 > 2 through gateway 1"), std::string::npos) << out;
  EXPECT_NE(out.find("reached"), std::string::npos) << out;
}

TEST(PlannerTools, GotoNoPathExitsFourAndCtrlCCancels)
{
  RGNAV_REQUIRE_NETNS();
  Stack s;
  s.hold(Pose2(1.0, 1.5, 0.0), 500ms);
  auto nowhere = s.go({"kitchen", "--goal-id", "41"}, "nowhere.out");
  const auto no_path = s.finish(nowhere, Pose2(1.0, 1.5, 0.0), 15s);
  ASSERT_TRUE(no_path.has_value());
  EXPECT_TRUE(no_path->exited && no_path->code == 4) << no_path->describe() << "\n" << read_file(s.dir.file("nowhere.out"));
  EXPECT_NE(read_file(s.dir.file("nowhere.out")).find("kitchen"), std::string::npos);

  auto go = s.go({"room_b", "--goal-id", "42"}, "cancelled.out");
  s.hold(Pose2(1.0, 1.5, 0.0), 2000ms);
  ASSERT_TRUE(go.running());
  ASSERT_TRUE(go.signal(SIGINT));
  const auto cancelled = s.finish(go, Pose2(1.0, 1.5, 0.0), 10s);
  ASSERT_TRUE(cancelled.has_value());
  EXPECT_TRUE(cancelled->exited && cancelled->code == 3) << cancelled->describe();
  s.hold(Pose2(1.0, 1.5, 0.0), 500ms);
  ASSERT_FALSE(s.paths.empty());
  EXPECT_EQ(s.paths.back().goal_id, 42);
  EXPECT_EQ(s.paths.back().status, global_path_t::STATUS_CANCELLED);
}

TEST(PlannerTools, ANameGivenWithNameRegionIsAGoalAtOnce)
{
  RGNAV_REQUIRE_NETNS();
  Stack s;
  s.hold(Pose2(1.0, 1.5, 0.0), 500ms);
  const auto named = run_to_completion({RGNAV_NAME_REGION_BIN, "2", "Lab 2", "--lcm-url", test_udpm_url()}, 20s);
  EXPECT_TRUE(named.clean()) << named.describe();
  s.hold(Pose2(1.0, 1.5, 0.0), 500ms);
  auto go = s.go({"lab 2", "--no-wait", "--goal-id", "51"}, "named.out");
  const auto status = s.finish(go, Pose2(1.0, 1.5, 0.0), 10s);
  ASSERT_TRUE(status.has_value());
  EXPECT_TRUE(status->clean()) << status->describe() << "\n" << read_file(s.dir.file("named.out"));
  s.hold(Pose2(1.0, 1.5, 0.0), 500ms);
  ASSERT_FALSE(s.paths.empty());
  EXPECT_EQ(s.paths.back().goal_id, 51);
  EXPECT_EQ(s.paths.back().status, global_path_t::STATUS_OK) << s.paths.back().reason;
  expect_clean_stop(*s.planner);
}

}  // namespace
}  // namespace rgnav::testing
