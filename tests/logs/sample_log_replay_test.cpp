// Replay regression over the checked-in sample logs (logs/samples/*.lcmlog): each log runs
// through the mapping pipeline exactly as `./rgnav map` runs it (scan mapper + gateway detector +
// RG kernel on message time), and the result must equal the summary checked in beside it
// (<log>.summary.json): every count exactly, every measure to 1e-6, and the last pose of the
// trajectory to 1 mm / 1 mrad. A change that moves the maps on purpose refreshes the summaries
// with RGNAV_UPDATE_SAMPLES=1 (see logs/README.md) and says so in its commit.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace rgnav {
namespace {

namespace fs = std::filesystem;

// Keys that measure the machine, not the map.
const std::vector<std::string> kTimingKeys = {"cpu_seconds", "realtime_factor"};

std::vector<fs::path> sample_logs()
{
  std::vector<fs::path> logs;
  for (const auto& e : fs::directory_iterator(RGNAV_SAMPLES_DIR))
    if (e.path().extension() == ".lcmlog") logs.push_back(e.path());
  std::sort(logs.begin(), logs.end());
  return logs;
}

nlohmann::json read_json(const fs::path& p)
{
  std::ifstream f(p);
  if (!f) throw std::runtime_error("cannot read " + p.string());
  return nlohmann::json::parse(f);
}

// The last accepted scan's final pose estimate: x, y, theta of trajectory.txt's last line.
std::vector<double> last_pose(const fs::path& trajectory)
{
  std::ifstream f(trajectory);
  std::string line, last;
  while (std::getline(f, line))
    if (!line.empty() && line[0] != '#') last = line;
  std::istringstream s(last);
  double id = 0, utime = 0, x = 0, y = 0, theta = 0;
  if (!(s >> id >> utime >> x >> y >> theta)) return {};
  return {x, y, theta};
}

// What the pipeline made of one log: its summary without timing keys, plus the last pose.
nlohmann::json replay(const fs::path& log, const fs::path& out)
{
  fs::remove_all(out);
  fs::create_directories(out.parent_path());
  const std::string cmd = std::string(RGNAV_MAP_SCRIPT) + " '" + log.string() + "' --out '" + out.string() +
                          "' --no-pictures > '" + out.string() + ".log' 2>&1";
  if (std::system(cmd.c_str()) != 0) {
    std::ifstream f(out.string() + ".log");
    std::stringstream ss;
    ss << f.rdbuf();
    throw std::runtime_error("rgnav map failed on " + log.string() + ":\n" + ss.str());
  }
  nlohmann::json j = read_json(out / "summary.json");
  for (const auto& k : kTimingKeys) j.erase(k);
  j["last_pose"] = last_pose(out / "trajectory.txt");
  return j;
}

void expect_same(const nlohmann::json& expected, const nlohmann::json& got, const std::string& where)
{
  for (const auto& [key, want] : expected.items()) {
    const std::string at = where + "." + key;
    if (!got.contains(key)) {
      ADD_FAILURE() << at << " is missing";
      continue;
    }
    const auto& have = got[key];
    if (key == "last_pose") {
      ASSERT_EQ(have.size(), 3u) << at;
      EXPECT_NEAR(have[0].get<double>(), want[0].get<double>(), 1e-3) << at << " x";
      EXPECT_NEAR(have[1].get<double>(), want[1].get<double>(), 1e-3) << at << " y";
      EXPECT_NEAR(have[2].get<double>(), want[2].get<double>(), 1e-3) << at << " theta";
    } else if (want.is_number_integer()) {
      EXPECT_EQ(have, want) << at;
    } else if (want.is_number()) {
      const double w = want.get<double>();
      EXPECT_NEAR(have.get<double>(), w, 1e-6 * std::max(1.0, std::abs(w))) << at;
    } else if (want.is_object()) {
      expect_same(want, have, at);
    } else {
      EXPECT_EQ(have, want) << at;
    }
  }
  for (const auto& [key, value] : got.items())
    EXPECT_TRUE(expected.contains(key)) << where << "." << key << " is new: refresh the summary";
}

TEST(SampleLogs, AreSmallEnoughToCheckIn)
{
  const auto logs = sample_logs();
  ASSERT_FALSE(logs.empty()) << "no sample log under " << RGNAV_SAMPLES_DIR;
  for (const auto& log : logs) EXPECT_LE(fs::file_size(log), 2u << 20) << log;
}

TEST(SampleLogs, ReplayThroughTheMappingPipelineGivesTheCheckedInSummary)
{
  const bool update = std::getenv("RGNAV_UPDATE_SAMPLES") != nullptr;
  const fs::path work = fs::path(RGNAV_TEST_OUTPUT_DIR) / "sample_replay";
  for (const auto& log : sample_logs()) {
    SCOPED_TRACE(log.string());
    fs::path expected_path = log;
    expected_path.replace_extension(".summary.json");
    const nlohmann::json got = replay(log, work / log.stem());
    if (update) {
      std::ofstream(expected_path) << got.dump(1) << "\n";
      continue;
    }
    ASSERT_TRUE(fs::exists(expected_path)) << "no " << expected_path << ": make it with RGNAV_UPDATE_SAMPLES=1";
    const nlohmann::json expected = read_json(expected_path);
    expect_same(expected, got, log.stem().string());
    // A replay that mapped nothing would match an empty summary: the samples must show a map.
    EXPECT_GT(expected.value("accepted_scans", 0), 40) << "the sample is too short to test mapping";
    EXPECT_GE(expected.value("regions", 0), 2) << "the sample should leave a region through a gateway";
  }
}

}  // namespace
}  // namespace rgnav
