// The supervisor's state file (issue 35): a file of random bytes, an empty one and one cut off
// mid-content are not used, moved aside as found (<path>.damaged), and the state is empty, so
// no stranger is adopted; a whole file round-trips.
#include <gtest/gtest.h>

#include <filesystem>

#include "bad_files.h"
#include "state_file.h"

namespace rgnav::supervisor {
namespace {

TEST(SupervisorStateFile, RoundTripsAndSetsAsideRandomBytesEmptyAndCutOffFiles)
{
  testing::TempDir dir("supervisor_state");
  SupervisorState s;
  s.host = "robot";
  s.launch_config = "sim.pmd";
  s.children.push_back({"lld", 4242, 99, {"lld", "--config", "x.yaml"}, 15, 1});
  s.done = {"tour"};
  save_state(dir.file("supervisor.json"), s);
  const SupervisorState back = load_state(dir.file("supervisor.json"));
  ASSERT_EQ(back.children.size(), 1u);
  EXPECT_EQ(back.children[0].argv, s.children[0].argv);
  EXPECT_EQ(back.done, s.done);
  EXPECT_TRUE(load_state(dir.file("missing.json")).children.empty());

  for (const auto& f : testing::write_bad_files(dir.path(), "supervisor.json", testing::read_file(dir.file("supervisor.json")))) {
    SCOPED_TRACE(f.kind);
    const std::string bytes = testing::read_file(f.path);
    const SupervisorState loaded = load_state(f.path);
    EXPECT_TRUE(loaded.children.empty());
    EXPECT_TRUE(loaded.done.empty());
    EXPECT_TRUE(loaded.host.empty());
    EXPECT_FALSE(std::filesystem::exists(f.path));
    EXPECT_EQ(testing::read_file(f.path + ".damaged"), bytes);
  }
}

}  // namespace
}  // namespace rgnav::supervisor
