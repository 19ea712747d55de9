// `./rgnav map` and `./rgnav replay` on bad files (issue 35): random bytes, an empty file, a log cut off inside its
// first event and a valid LCM log with no laser scans are refused: exit non-zero, the file named
// on stderr, no output folder. A sample log cut off in the middle is mapped up to the damage,
// with a warning naming the file.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>

#include "bad_files.h"

namespace rgnav::testing {
namespace {

namespace fs = std::filesystem;

ToolRun rgnav_map(const std::string& log, const std::string& out, const TempDir& dir)
{
  return run_tool({"env", "RGNAV_BUILD=" RGNAV_BUILD_DIR, "bash", RGNAV_MAP_SH, log, "--out", out, "--no-pictures"},
                  dir.path(), std::chrono::seconds(240));
}

std::string sample_bytes()
{
  std::string first;
  for (const auto& e : fs::directory_iterator(RGNAV_SAMPLES_DIR))
    if (e.path().extension() == ".lcmlog" && (first.empty() || e.path().string() < first)) first = e.path().string();
  return read_file(first);
}

TEST(MapBadFiles, NoLogAtAllIsRefusedNamingItAndWritesNothing)
{
  TempDir dir("map_bad_files");
  const std::string bytes = sample_bytes();
  ASSERT_GT(bytes.size(), 1000u);
  auto files = write_bad_files(dir.path(), "log.lcmlog", bytes);
  files.erase(files.begin() + 2);   // the truncated one has its own test
  files.push_back({"cut in the first event", dir.file("first_event.lcmlog")});
  write_bytes(files.back().path, bytes.substr(0, 60));
  files.push_back({"no laser scans", dir.file("odometry_only.lcmlog")});
  // One complete event on another channel: an LCM log, but nothing to map.
  const uint32_t channel_len = 3, data_len = 2;
  std::string event("\xed\xa1\xda\x01", 4);
  event += std::string(8, '\0') + std::string(8, '\0');
  for (const uint32_t v : {channel_len, data_len})
    for (int k = 3; k >= 0; --k) event.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
  event += "FOOab";
  write_bytes(files.back().path, event);
  for (const auto& f : files) {
    SCOPED_TRACE(f.kind);
    const std::string out = dir.file("out_" + fs::path(f.path).stem().string());
    const auto r = rgnav_map(f.path, out, dir);
    EXPECT_TRUE(r.status.exited && r.status.code != 0) << r.status.describe() << "\n" << r.err;
    EXPECT_NE(r.err.find(f.path), std::string::npos) << r.err;
    EXPECT_TRUE(nothing_written(out)) << out;
  }
}

TEST(MapBadFiles, LogCutOffInTheMiddleIsMappedUpToTheDamageWithAWarning)
{
  TempDir dir("map_cut_log");
  const std::string bytes = sample_bytes();
  const std::string cut = dir.file("cut.lcmlog");
  write_bytes(cut, bytes.substr(0, bytes.size() / 4 + 13));   // a quarter: mid-event, quick to map
  const std::string out = dir.file("out");
  const auto r = rgnav_map(cut, out, dir);
  EXPECT_TRUE(r.status.clean()) << r.status.describe() << "\n" << r.err;
  EXPECT_NE(r.err.find(cut + ": event"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(out + "/rgmap.json"));
  const auto summary = nlohmann::json::parse(read_file(out + "/summary.json"));
  EXPECT_GT(summary.value("scans", 0), 50) << summary.dump();
}

// ./rgnav replay checks its logs before it starts the stack: a file that is no log is refused
// naming it (nothing is started), a cut-off one gets a warning naming it and would be played.
TEST(ReplayBadFiles, NoLogAtAllIsRefusedBeforeAnythingStartsACutOffOneIsWarnedAbout)
{
  TempDir dir("replay_bad_files");
  const std::string bytes = sample_bytes();
  for (const auto& f : write_bad_files(dir.path(), "log.lcmlog", bytes, bytes.size() / 3 + 5)) {
    SCOPED_TRACE(f.kind);
    if (f.kind == "truncated") {
      const auto r = run_tool({RGNAV_BUILD_DIR "/bin/rgnav_log_check", f.path}, dir.path());
      EXPECT_TRUE(r.status.clean()) << r.err;
      EXPECT_NE(r.err.find(f.path + ": warning: "), std::string::npos) << r.err;
      EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
      continue;
    }
    const auto r = run_tool({"env", "RGNAV_BUILD=" RGNAV_BUILD_DIR, "bash", RGNAV_REPLAY_SH, f.path,
                             "--state-dir", dir.file("state")},
                            dir.path(), std::chrono::seconds(60));
    EXPECT_TRUE(r.status.exited && r.status.code != 0) << r.status.describe() << "\n" << r.err;
    EXPECT_NE(r.err.find(f.path), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("nothing was started"), std::string::npos) << r.err;
    EXPECT_TRUE(nothing_written(dir.file("state")));
  }
}

}  // namespace
}  // namespace rgnav::testing
