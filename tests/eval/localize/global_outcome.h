// How a global-localization trial of the benchmark ended (localize_trials.cpp), judged at the
// deadline (the first filter update at or after 10 s): the failures by cause, so that a miss
// the map makes unavoidable (the views seen by then fit another place as well as the true one)
// is told apart from one the localizer could have avoided.
#pragma once

#include "localizer/localizer.h"

namespace rgnav::localize_eval {

struct GlobalTrialEnd
{
  bool success = false;                    // claimed and right from some time <= the deadline to the end
  bool wrong_claim = false;                // claimed a place > 0.5 m wrong at some time
  bool unclaimed_at_deadline = false;      // still unsure at the deadline
  localizer::Unsure truth_at_deadline = localizer::Unsure::kNone;   // why_not_distinguishable(truth) then
  bool estimate_good_at_deadline = false;  // the unclaimed estimate was right then
};

// ok; wrong_claim; claimed_not_kept (claimed by the deadline, not kept right); unclaimed then:
// ambiguous_at_deadline (the views do not single out the true pose: no claim could have been
// right yet), unclaimed_estimate_right (the claim rule lags), unclaimed_estimate_elsewhere (the
// filter lags). A wrong claim counts before everything else: it is the worst outcome.
inline const char* outcome_class(const GlobalTrialEnd& t)
{
  if (t.success) return "ok";
  if (t.wrong_claim) return "wrong_claim";
  if (!t.unclaimed_at_deadline) return "claimed_not_kept";
  if (t.truth_at_deadline != localizer::Unsure::kNone) return "ambiguous_at_deadline";
  return t.estimate_good_at_deadline ? "unclaimed_estimate_right" : "unclaimed_estimate_elsewhere";
}

}  // namespace rgnav::localize_eval
