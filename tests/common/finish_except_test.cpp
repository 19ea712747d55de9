#include "config/finish_except.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace rgnav::config {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const char* kProcessConfig =
    "node:\n  name: mapper\nchannels:\n  scan: LASER_FRONT\n"
    "algo:\n  range_m: 30\n  step: 2\n";

std::string error_of(const Config& cfg, const std::vector<std::string>& process_sections)
{
  try {
    finish_except(cfg, process_sections);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(FinishExcept, AcceptsWhatWasReadAndTheProcessSections)
{
  const auto cfg = Config::parse(kProcessConfig, "p.yaml");
  const auto algo = cfg.section("algo");
  algo.number("range_m", 10, 1, 80);
  algo.integer("step", 1, 1, 10);
  EXPECT_EQ(error_of(cfg, {"node", "channels"}), "no error");
}

TEST(FinishExcept, RefusesAnUnreadKeyOfAReadSection)
{
  const auto cfg = Config::parse(kProcessConfig, "p.yaml");
  cfg.section("algo").number("range_m", 10, 1, 80);
  const std::string e = error_of(cfg, {"node", "channels"});
  EXPECT_THAT(e, HasSubstr("p.yaml"));
  EXPECT_THAT(e, HasSubstr("'algo.step'"));
  EXPECT_THAT(e, Not(HasSubstr("node.name")));
}

TEST(FinishExcept, RefusesASectionNobodyReads)
{
  // A misspelt section name: its keys would otherwise all fall back to their defaults.
  const auto cfg = Config::parse("node:\n  name: m\nalgoo:\n  range_m: 30\n", "p.yaml");
  cfg.section("algo").number("range_m", 10, 1, 80);
  EXPECT_THAT(error_of(cfg, {"node"}), HasSubstr("'algoo.range_m'"));
}

TEST(FinishExcept, ChecksProcessSectionsOnlyWhenNotExcepted)
{
  const auto cfg = Config::parse(kProcessConfig, "p.yaml");
  const auto algo = cfg.section("algo");
  algo.number("range_m", 10, 1, 80);
  algo.integer("step", 1, 1, 10);
  EXPECT_THAT(error_of(cfg, {"node"}), HasSubstr("'channels.scan'"));
}

}  // namespace
}  // namespace rgnav::config
