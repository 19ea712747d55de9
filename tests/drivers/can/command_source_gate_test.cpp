// The BASE_CMD owner rule on explicit time: the configured owner is followed, the hold's zero
// always wins, and a second source is refused at its first command (quick stop + an alert naming
// both) until it has been silent for foreign_quiet.
#include "base_driver/command_source_gate.h"

#include <gtest/gtest.h>

namespace rgnav::can::base {
namespace {

using namespace std::chrono_literals;
using Clock = CommandSourceGate::Clock;

CommandSourceOptions options()
{
  CommandSourceOptions o;
  o.owner = "lld";
  o.hold_source = "supervisor";
  o.foreign_quiet = 1000ms;
  return o;
}

TEST(CommandSourceGate, OwnerIsFollowedAndASecondSourceIsRefusedAtItsFirstCommand)
{
  CommandSourceGate g(options());
  const Clock::time_point t0{};
  EXPECT_EQ(g.on_command("lld", 0.3, 0.0, 150ms, t0).verdict, CommandVerdict::kFollow);
  EXPECT_FALSE(g.locked_out(t0));

  // The very first command of another source: quick stop, with an alert naming both.
  const auto d = g.on_command("teleop", 0.5, 0.1, 150ms, t0 + 50ms);
  EXPECT_EQ(d.verdict, CommandVerdict::kQuickStop);
  EXPECT_NE(d.alert.find("'teleop'"), std::string::npos) << d.alert;
  EXPECT_NE(d.alert.find("'lld'"), std::string::npos) << d.alert;
  EXPECT_TRUE(g.locked_out(t0 + 50ms));
  EXPECT_EQ(g.refused(), 1);

  // The owner is not followed while the other one speaks (they would fight); the alert is not
  // repeated for every command of the same source.
  EXPECT_EQ(g.on_command("lld", 0.3, 0.0, 150ms, t0 + 100ms).verdict, CommandVerdict::kQuickStop);
  const auto again = g.on_command("teleop", 0.5, 0.1, 150ms, t0 + 100ms);
  EXPECT_EQ(again.verdict, CommandVerdict::kQuickStop);
  EXPECT_TRUE(again.alert.empty());
  // A third source is news again.
  EXPECT_NE(g.on_command("lld2", 0.2, 0.0, 150ms, t0 + 150ms).alert.find("'lld2'"), std::string::npos);

  // Silent for foreign_quiet: the owner drives again.
  EXPECT_TRUE(g.locked_out(t0 + 1149ms));
  EXPECT_EQ(g.on_command("lld", 0.3, 0.0, 150ms, t0 + 1149ms).verdict, CommandVerdict::kQuickStop);
  EXPECT_FALSE(g.locked_out(t0 + 1150ms));
  EXPECT_EQ(g.on_command("lld", 0.3, 0.0, 150ms, t0 + 1150ms).verdict, CommandVerdict::kFollow);
  // The alert stays readable for the record.
  EXPECT_NE(g.alert().find("'lld2'"), std::string::npos);
}

TEST(CommandSourceGate, TheHoldsZeroWinsOverTheOwnerForItsDeadlineAndRaisesNoAlert)
{
  CommandSourceGate g(options());
  const Clock::time_point t0{};
  const auto hold = g.on_command("supervisor", 0.0, 0.0, 100ms, t0);
  EXPECT_EQ(hold.verdict, CommandVerdict::kStop);
  EXPECT_TRUE(hold.alert.empty());
  EXPECT_FALSE(g.locked_out(t0));
  // lld restarted and commanding while the hold is still on: zero.
  EXPECT_EQ(g.on_command("lld", 0.3, 0.0, 150ms, t0 + 60ms).verdict, CommandVerdict::kStop);
  EXPECT_EQ(g.on_command("lld", 0.3, 0.0, 150ms, t0 + 99ms).verdict, CommandVerdict::kStop);
  // The hold stopped (its last command expired): lld drives.
  EXPECT_EQ(g.on_command("lld", 0.3, 0.0, 150ms, t0 + 100ms).verdict, CommandVerdict::kFollow);
  EXPECT_EQ(g.refused(), 0);
}

TEST(CommandSourceGate, TheHoldSourceCommandingMotionIsASecondSource)
{
  CommandSourceGate g(options());
  const auto d = g.on_command("supervisor", 0.2, 0.0, 100ms, Clock::time_point{});
  EXPECT_EQ(d.verdict, CommandVerdict::kQuickStop);
  EXPECT_NE(d.alert.find("'supervisor'"), std::string::npos) << d.alert;
  EXPECT_NE(d.alert.find("only command zero"), std::string::npos) << d.alert;
  EXPECT_TRUE(g.locked_out(Clock::time_point{}));
}

TEST(CommandSourceGate, UnprintableAndEmptySourcesAreNamedSafely)
{
  CommandSourceGate g(options());
  const auto d = g.on_command(std::string("evil\n\x01name") + std::string(100, 'x'), 0.1, 0.0, 100ms, Clock::time_point{});
  EXPECT_EQ(d.verdict, CommandVerdict::kQuickStop);
  EXPECT_EQ(d.alert.find('\n'), std::string::npos);
  EXPECT_NE(d.alert.find("evil??name"), std::string::npos) << d.alert;
  EXPECT_LT(d.alert.size(), 300u);
  CommandSourceGate g2(options());
  EXPECT_NE(g2.on_command("", 0.0, 0.0, 100ms, Clock::time_point{}).alert.find("(no source)"), std::string::npos);
}

}  // namespace
}  // namespace rgnav::can::base
