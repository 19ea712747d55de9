// `./rgnav spy` end to end: lcm-spy (lcm.spy.Spy with the rgnav jar, as deploy/cli/spy.sh
// starts it) under Xvfb, with a runtime process publishing every rgnav message type. SpyCheck
// (java/SpyCheck.java) reads spy's channel table in its window: each channel must show its rgnav
// type, not "?? <fingerprint>", with no undecodable messages; and the window must not be blank.
#include <gtest/gtest.h>

#include "bus_watch.h"
#include "child_process.h"

namespace rgnav::testing {
namespace {

using std::chrono::seconds;

const char* kExpected =
    "CONTRACT_laser_scan_t=laser_scan_t,CONTRACT_odometry_t=odometry_t,CONTRACT_stereo_images_t=stereo_images_t,"
    "CONTRACT_rg_map_t=rg_map_t,CONTRACT_trajectory_t=trajectory_t,CONTRACT_supervisor_status_t=supervisor_status_t,"
    "CONTRACT_gateway_hypotheses_t=gateway_hypotheses_t,HEARTBEAT=heartbeat_t";

class Spy : public ::testing::Test
{
 protected:
  void SetUp() override
  {
    RGNAV_REQUIRE_NETNS();
    if (std::string(RGNAV_XVFB_RUN).empty()) GTEST_SKIP() << "xvfb-run not installed (Debian package xvfb)";
    auto args = std::vector<std::string>{RGNAV_CONTRACT_PUBLISHER, "--config",
                                         std::string(RGNAV_INTEGRATION_CONFIG_DIR) + "/contract_publisher.yaml",
                                         "--lcm-url", test_udpm_url(), "--rounds", "1000"};
    ChildOptions o;
    o.stderr_path = dir_.file("publisher.stderr");
    publisher_.emplace(args, o);
    HeartbeatWatch watch(test_udpm_url());
    ASSERT_TRUE(watch.wait_for("contract_publisher", seconds(20), publisher_->pid())) << publisher_->stderr_text();
  }

  ExitStatus spy_check(const std::string& classpath, int timeout_s, const std::string& screenshot)
  {
    ChildOptions o;
    o.stdout_path = dir_.file("spy.stdout");
    o.stderr_path = dir_.file("spy.stderr");
    return run_to_completion({RGNAV_XVFB_RUN, "-a", "-s", "-screen 0 1280x900x24", RGNAV_JAVA,
                              "-Djava.net.preferIPv4Stack=true", "-cp", classpath, "SpyCheck",
                              std::to_string(timeout_s), screenshot, kExpected, "--lcm-url", test_udpm_url()},
                             seconds(timeout_s + 60), o);
  }

  std::string output() const { return read_file(dir_.file("spy.stdout")) + read_file(dir_.file("spy.stderr")); }

  TempDir dir_{"rgnav_spy"};
  std::optional<ChildProcess> publisher_;
};

TEST_F(Spy, ShowsRgnavTypeNamesForLiveChannels)
{
  const std::string classpath = std::string(RGNAV_LCM_JAR) + ":" + RGNAV_JCHART2D_JAR + ":" + RGNAV_TYPES_JAR +
                                ":" + RGNAV_CHECK_JAR;
  const std::string screenshot = std::string(RGNAV_TEST_OUTPUT_DIR) + "/spy_test_screenshot.png";
  const auto status = spy_check(classpath, 60, screenshot);
  EXPECT_TRUE(status.clean()) << status.describe() << "\n" << output();
  EXPECT_NE(output().find("OK: 8 rgnav channels decoded"), std::string::npos) << output();
  EXPECT_FALSE(read_file(screenshot).empty());
  EXPECT_TRUE(publisher_->stop(seconds(10)).clean());
}

TEST_F(Spy, CheckFailsWithoutTheRgnavJar)
{
  // Same, without the rgnav classes: spy can only show "?? <fingerprint>", and the check says so.
  const std::string classpath = std::string(RGNAV_LCM_JAR) + ":" + RGNAV_JCHART2D_JAR + ":" + RGNAV_CHECK_JAR;
  const auto status = spy_check(classpath, 8, dir_.file("no_types.png"));
  EXPECT_TRUE(status.exited && status.code == 1) << status.describe() << "\n" << output();
  EXPECT_NE(output().find("shown as '??"), std::string::npos) << output();
}

}  // namespace
}  // namespace rgnav::testing
