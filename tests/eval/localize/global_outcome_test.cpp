// The benchmark's outcome classes of a global-localization trial (global_outcome.h): a wrong
// claim is never hidden under another class, and an unclaimed trial is ambiguous only when the
// truth itself was not distinguishable at the deadline.
#include <gtest/gtest.h>

#include <string>

#include "global_outcome.h"

namespace rgnav::localize_eval {
namespace {

using localizer::Unsure;

TEST(GlobalOutcome, AWrongClaimCountsBeforeEverythingButSuccess)
{
  GlobalTrialEnd t;
  t.wrong_claim = true;
  t.unclaimed_at_deadline = true;   // claimed wrong early, unsure again at the deadline
  t.truth_at_deadline = Unsure::kRival;
  EXPECT_EQ(std::string(outcome_class(t)), "wrong_claim");
  t.success = true;                 // corrected before the deadline and kept
  EXPECT_EQ(std::string(outcome_class(t)), "ok");
}

TEST(GlobalOutcome, UnclaimedTrialsSplitByWhatTheTruthExplains)
{
  GlobalTrialEnd t;
  t.unclaimed_at_deadline = true;
  t.truth_at_deadline = Unsure::kRival;
  EXPECT_EQ(std::string(outcome_class(t)), "ambiguous_at_deadline");
  t.truth_at_deadline = Unsure::kPathElsewhere;
  EXPECT_EQ(std::string(outcome_class(t)), "ambiguous_at_deadline");
  t.truth_at_deadline = Unsure::kNone;
  EXPECT_EQ(std::string(outcome_class(t)), "unclaimed_estimate_elsewhere");
  t.estimate_good_at_deadline = true;
  EXPECT_EQ(std::string(outcome_class(t)), "unclaimed_estimate_right");
}

TEST(GlobalOutcome, ClaimedInTimeButNotKept)
{
  GlobalTrialEnd t;
  t.unclaimed_at_deadline = false;
  t.truth_at_deadline = Unsure::kRival;   // not asked when claimed; must not matter
  EXPECT_EQ(std::string(outcome_class(t)), "claimed_not_kept");
}

}  // namespace
}  // namespace rgnav::localize_eval
