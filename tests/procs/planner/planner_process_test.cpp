// The planner as a process and its operator tools, on memq:// (nothing leaves the process, no
// network namespace needed): the shipped config passes --check-config and a misspelt key is
// refused naming file and key; the planner starts on a saved map, exits 0 on SIGTERM and saves
// its state on the way out; ./rgnav goto and ./rgnav name-region accept what they should and
// refuse the rest, and name-region --map writes the name into the saved map.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <thread>

#include "child_process.h"
#include "planner/planner_state.h"
#include "rgmap/saved_map.h"
#include "two_room_map.h"

namespace rgnav::planner {
namespace {

using namespace std::chrono_literals;

bool wait_for_text(const std::string& path, const std::string& text, std::chrono::milliseconds timeout)
{
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < until) {
    if (testing::read_file(path).find(text) != std::string::npos) return true;
    std::this_thread::sleep_for(50ms);
  }
  return false;
}

TEST(PlannerProcess, ShippedConfigPassesCheckConfigAndAMisspeltKeyIsRefused)
{
  testing::TempDir dir("planner_config");
  testing::ChildOptions o;
  o.stderr_path = dir.file("stderr");
  auto status = testing::run_to_completion({RGNAV_PLANNER_BIN, "--config", RGNAV_SOURCE_DIR "/config/planner.yaml", "--check-config"},
                                           30s, o);
  EXPECT_TRUE(status.clean()) << status.describe() << testing::read_file(dir.file("stderr"));
  {
    std::ifstream in(RGNAV_SOURCE_DIR "/config/planner.yaml");
    std::ofstream out(dir.file("planner.yaml"));
    std::string line;
    while (std::getline(in, line)) {
      const auto at = line.find("blocked_after_s");
      if (at != std::string::npos) line.replace(at, 15, "blocked_aftr_s");
      out << line << "\n";
    }
  }
  status = testing::run_to_completion({RGNAV_PLANNER_BIN, "--config", dir.file("planner.yaml"), "--check-config"}, 30s, o);
  EXPECT_TRUE(status.exited && status.code == 2) << status.describe();
  const std::string err = testing::read_file(dir.file("stderr"));
  EXPECT_NE(err.find(dir.file("planner.yaml")), std::string::npos) << err;
  EXPECT_NE(err.find("execution.blocked_aftr_s"), std::string::npos) << err;
}

TEST(PlannerProcess, StartsOnASavedMapAndExitsCleanlyOnSigterm)
{
  testing::TempDir dir("planner_process");
  testing::write_rgmap_json(testing::two_room_world().map, dir.file("map"));
  testing::ChildOptions o;
  o.stderr_path = dir.file("stderr");
  testing::ChildProcess p({RGNAV_PLANNER_BIN, "--lcm-url", "memq://", "--map", dir.file("map"), "--state-file",
                           dir.file("state/planner.json")},
                          o);
  ASSERT_TRUE(wait_for_text(dir.file("stderr"), "map version 1 from", 20s)) << testing::read_file(dir.file("stderr"));
  ASSERT_TRUE(p.running());
  ASSERT_TRUE(p.signal(SIGTERM));
  const auto status = p.wait_for(10s);
  ASSERT_TRUE(status.has_value()) << "still running 10 s after SIGTERM";
  EXPECT_TRUE(status->clean()) << status->describe() << "\n" << testing::read_file(dir.file("stderr"));
  // Its stop saved the state (nothing learned, no goal: still a state to start from).
  const auto saved = load_planner_state(dir.file("state/planner.json"));
  ASSERT_TRUE(saved.has_value());
  EXPECT_FALSE(saved->goal.has_value());
}

TEST(PlannerProcess, GotoSendsValidGoalsOnly)
{
  // memq:// keeps the goal inside the tool, where no planner answers: a goal it accepts is sent
  // (again every second) until --answer-timeout, then it gives up (exit 1, never waits forever);
  // one it refuses is exit 2 at once.
  const auto run = [](std::vector<std::string> args) {
    args.insert(args.begin(), RGNAV_GOTO_BIN);
    args.insert(args.end(), {"--lcm-url", "memq://", "--answer-timeout", "1"});
    return testing::run_to_completion(args, 30s);
  };
  for (const auto& good : std::vector<std::vector<std::string>>{
           {"room_b", "--no-wait"}, {"2", "1.5", "0.5", "-45", "--tolerance", "0.2", "--heading-tolerance", "10"}}) {
    const auto status = run(good);
    EXPECT_TRUE(status.exited && status.code == 1) << status.describe() << " for " << ::testing::PrintToString(good);
  }
  for (const auto& bad : std::vector<std::vector<std::string>>{{"--no-wait"},
                                                               {"room_b", "1", "2"},
                                                               {"room_b", "1", "nan", "0"},
                                                               {std::string(100, 'x')},
                                                               {"room_b", "--tolerance", "-1"}}) {
    const auto status = run(bad);
    EXPECT_TRUE(status.exited && status.code == 2) << status.describe() << " for " << ::testing::PrintToString(bad);
  }
}

TEST(PlannerProcess, NameRegionWritesTheSavedMapAndRefusesBadNames)
{
  testing::TempDir dir("planner_name");
  const auto world = testing::two_room_world();
  testing::write_rgmap_json(world.map, dir.file("map"));
  const auto run = [](std::vector<std::string> args) {
    args.insert(args.begin(), RGNAV_NAME_REGION_BIN);
    args.insert(args.end(), {"--lcm-url", "memq://"});
    return testing::run_to_completion(args, 30s);
  };
  EXPECT_TRUE(run({"2", "Lab 2", "--map", dir.file("map")}).clean());
  const auto map = rgmap::load_saved_map(dir.file("map"));
  EXPECT_EQ(map.region(world.room_b)->name, "Lab 2");
  EXPECT_EQ(map.version, world.map.version + 1);
  // Refused, and the map left as it was: unknown region, another region's name, bad names.
  for (const auto& bad : std::vector<std::vector<std::string>>{{"9", "hall", "--map", dir.file("map")},
                                                               {"2", "ROOM_A", "--map", dir.file("map")},
                                                               {"2", "42"},
                                                               {"2", " lab"},
                                                               {"2", std::string(65, 'x')},
                                                               {"0", "lab"}}) {
    const auto status = run(bad);
    EXPECT_TRUE(status.exited && status.code == 2) << status.describe() << " for " << ::testing::PrintToString(bad);
  }
  EXPECT_EQ(rgmap::load_saved_map(dir.file("map")).version, world.map.version + 1);
  // Without --map it only sends.
  EXPECT_TRUE(run({"2", "lab"}).clean());
}

}  // namespace
}  // namespace rgnav::planner
