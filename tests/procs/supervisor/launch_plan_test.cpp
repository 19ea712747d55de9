#include "launch_plan.h"

#include <gtest/gtest.h>

namespace rgnav::supervisor {
namespace {

PlanOptions options(bool allow_missing = false) { return {"/tmp", "", allow_missing}; }

std::string plan_error(const std::string& text, bool allow_missing = false)
{
  try {
    make_plan(parse_launch_text(text, "p.pmd"), options(allow_missing));
  } catch (const LaunchError& e) {
    return e.what();
  }
  return "";
}

TEST(LaunchPlan, StartsDependenciesFirstAndKeepsFileOrderOtherwise)
{
  const auto plan = make_plan(parse_launch_text(R"(
cmd "c" { exec = "true"; depends = "b"; }
cmd "a" { exec = "true"; }
cmd "b" { exec = "/bin/true --x 'two words' ${HOME}"; depends = "a"; }
cmd "d" { exec = "true"; }
)",
                                                "p.pmd"),
                              options());
  ASSERT_EQ(plan.commands.size(), 4u);
  EXPECT_EQ(plan.commands[0].spec.name, "a");
  EXPECT_EQ(plan.commands[1].spec.name, "b");
  EXPECT_EQ(plan.commands[2].spec.name, "c");
  EXPECT_EQ(plan.commands[3].spec.name, "d");
  const auto& b = plan.commands[1];
  EXPECT_EQ(b.executable, "/bin/true");
  ASSERT_EQ(b.argv.size(), 4u);
  EXPECT_EQ(b.argv[2], "two words");
  EXPECT_EQ(b.argv[3], std::getenv("HOME"));
}

TEST(LaunchPlan, ReportsEveryProblemWithFileAndLine)
{
  const std::string e = plan_error(R"(cmd "a" { exec = "true"; depends = "ghost"; }
cmd "a" { exec = "true"; }
cmd "x" { exec = "no_such_program_rgnav"; }
cmd "y" { exec = "true"; depends = "z"; }
cmd "z" { exec = "true"; depends = "y"; }
cmd "w" { exec = "true"; config = "config/none.yaml"; }
script "s" { start cmd "nobody"; stop group "nogroup"; run_script "none"; }
)");
  EXPECT_NE(e.find("p.pmd:1: command \"a\" depends on unknown process \"ghost\""), std::string::npos) << e;
  EXPECT_NE(e.find("p.pmd:2: duplicate command name \"a\" (first at p.pmd:1)"), std::string::npos) << e;
  EXPECT_NE(e.find("p.pmd:3: missing executable \"no_such_program_rgnav\""), std::string::npos) << e;
  EXPECT_NE(e.find("dependency cycle: y -> z -> y"), std::string::npos) << e;
  EXPECT_NE(e.find("p.pmd:6: command \"w\": config file \"config/none.yaml\" not found"), std::string::npos) << e;
  EXPECT_NE(e.find("p.pmd:7: script \"s\" names unknown process \"nobody\""), std::string::npos) << e;
  EXPECT_NE(e.find("names unknown group \"nogroup\""), std::string::npos) << e;
  EXPECT_NE(e.find("runs unknown script \"none\""), std::string::npos) << e;
}

TEST(LaunchPlan, MissingExecutablesCanBeListedInsteadOfRefused)
{
  const auto plan = make_plan(parse_launch_text("cmd \"x\" { exec = \"no_such_program_rgnav\"; }", "p"), options(true));
  ASSERT_EQ(plan.missing.size(), 1u);
  EXPECT_TRUE(plan.commands[0].executable.empty());
}

TEST(LaunchPlan, UndefinedVariableInExecIsAnError)
{
  EXPECT_NE(plan_error("cmd \"x\" {\n exec = \"${RGNAV_SURELY_UNDEFINED}/bin/x\"; }").find("p.pmd:2: exec \"${RGNAV_SURELY_UNDEFINED}/bin/x\": undefined variable"),
            std::string::npos);
}

TEST(LaunchPlan, ConfigPathExpandsVariablesAndAUndefinedOneIsAnError)
{
  setenv("RGNAV_PLAN_TEST_DIR", "/etc", 1);
  const auto plan = make_plan(parse_launch_text(R"(cmd "a" { exec = "true"; config = "${RGNAV_PLAN_TEST_DIR}/hostname"; oneshot = "true"; })", "p.pmd"),
                              options());
  ASSERT_EQ(plan.commands.size(), 1u);
  EXPECT_TRUE(plan.commands[0].spec.oneshot);
  ASSERT_EQ(plan.commands[0].argv.size(), 3u);
  EXPECT_EQ(plan.commands[0].argv[2], "/etc/hostname");
  const auto err = plan_error(R"(cmd "a" { exec = "true"; config = "${RGNAV_PLAN_TEST_UNDEFINED}/x.yaml"; })");
  EXPECT_NE(err.find("p.pmd:1"), std::string::npos) << err;
  EXPECT_NE(err.find("undefined variable"), std::string::npos) << err;
}

}  // namespace
}  // namespace rgnav::supervisor
