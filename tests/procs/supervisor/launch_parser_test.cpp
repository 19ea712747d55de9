#include "launch_parser.h"

#include <gtest/gtest.h>

#include "bad_files.h"

namespace rgnav::supervisor {
namespace {

TEST(LaunchParser, ReadsProcmanSyntaxWithGroupsScriptsAndExtensions)
{
  const auto cfg = parse_launch_text(R"(
# a comment
cmd "sim" { exec = "rgnav_sim --world x"; host = "b21r-main"; auto_respawn = "true"; stop_signal = 15; stop_time_allowed = 7; }
group "drivers" {
    cmd "laser_driver" {
        exec = "laser_driver";
        depends = "sim, base_driver";
        env = "A=1,B=two";
        config = "config/laser_driver.yaml";
        inputs = "X";
    }
    group "motion" { cmd "base_driver" { exec = "base_driver"; heartbeat_timeout_ms = 800; safety_critical = "true"; } }
}
script "bringup" {
    start cmd "sim" wait "running";
    wait ms 500;
    stop group "drivers";
    restart everything;
    wait cmd "sim" status "stopped";
    run_script "bringup";
}
)",
                                     "t.pmd");
  ASSERT_EQ(cfg.commands.size(), 3u);
  EXPECT_EQ(cfg.commands[0].name, "sim");
  EXPECT_EQ(cfg.commands[0].host, "b21r-main");
  EXPECT_EQ(cfg.commands[0].stop_signal, 15);
  EXPECT_DOUBLE_EQ(cfg.commands[0].stop_time_allowed_s, 7.0);
  EXPECT_EQ(cfg.commands[0].where.line, 3);
  const auto& laser = cfg.commands[1];
  EXPECT_EQ(laser.group, "drivers");
  EXPECT_EQ(laser.depends, (std::vector<std::string>{"sim", "base_driver"}));
  ASSERT_EQ(laser.env.size(), 2u);
  EXPECT_EQ(laser.env[1].second, "two");
  EXPECT_EQ(laser.config, "config/laser_driver.yaml");
  EXPECT_EQ(cfg.commands[2].group, "drivers/motion");
  EXPECT_EQ(cfg.commands[2].heartbeat_timeout_ms, 800);
  EXPECT_TRUE(cfg.commands[2].safety_critical);
  EXPECT_EQ(cfg.in_group("drivers").size(), 2u);
  EXPECT_EQ(cfg.in_group("motion").size(), 1u);
  ASSERT_EQ(cfg.scripts.size(), 1u);
  const auto& a = cfg.scripts[0].actions;
  ASSERT_EQ(a.size(), 6u);
  EXPECT_EQ(a[0].wait_status, "running");
  EXPECT_EQ(a[1].kind, ScriptAction::Kind::kWaitMs);
  EXPECT_EQ(a[1].delay_ms, 500);
  EXPECT_EQ(a[2].target, ScriptAction::Target::kGroup);
  EXPECT_EQ(a[3].target, ScriptAction::Target::kEverything);
  EXPECT_EQ(a[4].kind, ScriptAction::Kind::kWaitStatus);
  EXPECT_EQ(a[5].kind, ScriptAction::Kind::kRunScript);
}

std::string error_of(const std::string& text)
{
  try {
    parse_launch_text(text, "bad.pmd");
  } catch (const LaunchError& e) {
    return e.what();
  }
  return "";
}

TEST(LaunchParser, ErrorsNameFileAndLine)
{
  EXPECT_EQ(error_of("cmd \"a\" {\n  exec = \"x\n}"), "bad.pmd:2: unterminated string constant");
  EXPECT_NE(error_of("cmd \"a\" {\n exec = \"x\";\n colour = \"red\";\n}").find("bad.pmd:3: unknown attribute 'colour'"), std::string::npos);
  EXPECT_NE(error_of("\n\ncmd \"a\" { host = \"h\"; }").find("bad.pmd:3: command \"a\" has no exec"), std::string::npos);
  EXPECT_NE(error_of("cmd \"a\" { exec = \"x\" }").find("bad.pmd:1: expected ';'"), std::string::npos);
  EXPECT_NE(error_of("cmd \"a\" { exec = \"x\"; auto_respawn = \"maybe\"; }").find("must be \"true\" or \"false\""), std::string::npos);
  EXPECT_NE(error_of("group \"g\" {\n cmd \"a\" { exec = \"x\"; }\n").find("bad.pmd:3: expected '}' closing group"), std::string::npos);
  EXPECT_NE(error_of("script \"s\" {\n wait cmd \"a\" status \"sleeping\";\n}").find("bad.pmd:2:"), std::string::npos);
  EXPECT_NE(error_of("cmd \"a/b\" { exec = \"x\"; }").find("'/' is not allowed"), std::string::npos);
}

// Issue 35: a launch file of random bytes, an empty one and one cut off mid-content are refused
// naming the file (the supervisor and rgnav_ctl then refuse to start).
TEST(LaunchParser, RandomBytesEmptyAndCutOffFilesAreRefusedNamingThem)
{
  testing::TempDir dir("launch_bad");
  const std::string valid =
      "# robot\ngroup \"drivers\" {\n  cmd \"base\" { exec = \"base_driver --config a.yaml\"; }\n}\n"
      "cmd \"lld\" { exec = \"lld\"; depends = \"base\"; }\n";
  testing::write_bytes(dir.file("valid.pmd"), valid);
  EXPECT_EQ(parse_launch_file(dir.file("valid.pmd")).commands.size(), 2u);
  for (const auto& f : testing::write_bad_files(dir.path(), "launch.pmd", valid, valid.find("base_driver"))) {
    SCOPED_TRACE(f.kind);
    try {
      parse_launch_file(f.path);
      ADD_FAILURE() << f.path << " was read";
    } catch (const LaunchError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(f.path + ":", 0), 0u) << e.what();
    }
  }
  // Comments only (cut off in its header) or groups without commands: nothing to launch.
  testing::write_bytes(dir.file("comments.pmd"), "# robot launch\n");
  EXPECT_THROW(parse_launch_file(dir.file("comments.pmd")), LaunchError);
}

TEST(LaunchParser, UnnamedCommandTakesItsExecutableName)
{
  const auto cfg = parse_launch_text("cmd { exec = \"/usr/bin/lcm-spy --x\"; }", "t");
  ASSERT_EQ(cfg.commands.size(), 1u);
  EXPECT_EQ(cfg.commands[0].name, "lcm-spy");
}

}  // namespace
}  // namespace rgnav::supervisor
