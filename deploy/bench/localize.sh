#!/usr/bin/env bash
# ./rgnav bench localize: the localizer (procs/localizer) on RG maps built by rgnav's own pipeline
# (scan mapper + gateway detector + RG kernel, one lap of each world's tour), then simulated drives
# with config/sim.yaml's odometry error and walking people (worlds without people get three
# walkers pacing stretches of the tour) against the simulator's truth. Writes
# logs/bench/localize.json; maps, drives and MRPT's runs under logs/bench/localize/<world>/.
#
# Errors are measured in the estimate's region frame: every region is placed in the world by the
# rigid fit of its own scans' positions to their true positions (a region's line map carries the
# SLAM error of its scans; one fit of the whole map would count the map's global drift as
# localization error). region_fit_rmse_m_* per world says how well those fits hold.
#   tracking_*: the tour driven `--laps 2` times from the true start pose (operator-given, 0.1 m /
#     5 deg spread): RMSE / p95 / max of translation and rotation error per filter update;
#     handovers = times the estimate moved to a neighbouring region; divergences = times the error
#     went above 0.5 m; false_kidnaps = kidnap flags raised while tracking; gateway_passed_events.
#   global_*: 50 random starts per world (a random point of the tour, 30 s drive along it) from an
#     unknown pose: success = the localizer claims the pose (tracking mode) and is within 0.3 m /
#     10 deg from some time <= 10 s on to the end of the drive; time and distance driven until then
#     (p50 over the trials that got there). global_estimate_success_ratio: the same for its best
#     estimate whether claimed or not (in a building that repeats itself the localizer rightly
#     stays unsure); global_wrong_claims: trials in which it claimed a pose > 0.5 m wrong;
#     global_ambiguous_trials (per world global.ambiguous): failed trials that ended unsure where
#     a place >= unique_distance_m from the true pose (or turned) explains the views of the
#     robot's last view_path_length_m as well as the true pose does (Localizer::distinguishable
#     asked of the truth: the map repeats itself there); global_success_ratio_unambiguous: the
#     success ratio over the other trials.
#     global_classes (per world global.classes): every trial by its outcome, judged at the first
#     update at or after 10 s: ok; wrong_claim; claimed_not_kept (claimed by then, not kept within
#     0.3 m / 10 deg); ambiguous_at_deadline (unclaimed, and the views seen by then do not single
#     out the true pose: Localizer::why_not_distinguishable asked of the truth at that update, so no
#     claim could have been right yet); unclaimed_estimate_right / unclaimed_estimate_elsewhere
#     (unclaimed though the views single the truth out: the claim rule or the filter lags);
#     tests/eval/localize/global_outcome.h.
#     global_ambiguous_at_deadline_trials and global_success_ratio_distinguishable_at_deadline
#     (the success ratio over the other trials) follow from them.
#   kidnap_*: 10 per world: 10 s tracking, then the robot is carried >= 5 m elsewhere (its odometry
#     goes on) and driven 40 s: flag time (p50), recovered within 30 s and staying (ratio).
#   cpu_core_share: localizer CPU over simulated time in the tracking drives (one core = 1);
#     cpu_ms_per_update_p50, particles_mean, map_memory_mb_max (distance fields + bitmaps);
#     per world map_load_ms (the fields built from a new map).
#     global_cpu_ms_per_update_p50 / _p99 (per world global.cpu_ms_per_update_*): the filter
#     updates of the global trials, the searches made while unsure included.
#   Per world also: gateway_link_error_m_* (a gateway's transform between its regions against
#     their true placement, at the gateway: the map's own inconsistency at a hand-over),
#     region_fit_rmse_m_* (the per-region fits).
#   mrpt_*: MRPT's pf-localization (mrpt-apps) on the same drives (every 3rd scan, CARMEN log with
#     the log's own times) and an occupancy grid composed from the same RG map, scored the same
#     way (deploy/bench/mrpt/README.md): mrpt_tracking_rmse_m, mrpt_global_success_ratio
#     (on the first 10 global trials per world) and its per-world figures under mrpt.<world>.
# Env: LOCALIZE_ONLY (space-separated world names) runs only those; LOCALIZE_ARGS adds bench
#   flags (e.g. "--global-trials 10 --kidnaps 3"); LOCALIZE_MRPT=0 skips MRPT; LOCALIZE_TRACE=1
#   writes every tracking update (estimate, truth, error, cluster share, inliers) to
#   <world>/tracking_trace.txt and a line per global trial, kidnap and gateway link to stderr (a
#   trial's line counts its updates by the reason the localizer stayed unsure: Localizer::unsure,
#   and gives its class; unclaimed at the deadline, also the estimate's claim test and the
#   truth's lead as that test counts it: Localizer::claim_test); LOCALIZE_GLOBAL_TRIALS=
#   "world:trial ..." drives only those global trials, LOCALIZE_KIDNAP_TRIALS only those kidnaps
#   ("none" for none), each from the start it has in a full run (the ratios then count only them);
#   LOCALIZE_SKIP_TRACKING=1 skips the tracking drives (their keys then say nothing).
# The benchmark itself: tests/eval/localize (rgnav_localize_bench).
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
JSON="$ROOT/logs/bench/localize.json"
WORK="$ROOT/logs/bench/localize"
ONLY="${LOCALIZE_ONLY:-}"
# shellcheck source=lib/nav_worlds.sh
source "$ROOT/deploy/bench/lib/nav_worlds.sh"
bin="$BUILD/bin/rgnav_localize_bench"
[ -x "$bin" ] || { echo "bench localize: $bin is not built" >&2; exit 1; }
nav_world_args
mkdir -p "$WORK"
# shellcheck disable=SC2086
"$bin" --json "$JSON.rgnav" --out "$WORK" "${world_args[@]}" ${LOCALIZE_ARGS:-}
mrpt_ok=0
if [ "${LOCALIZE_MRPT:-1}" != 0 ] && command -v pf-localization >/dev/null; then
  # The MRPT pipeline checked first on a synthetic world with exact truth (frames, laser mount,
  # map origin, rawlog time stamps): a broken pipeline gives no MRPT figures at all.
  if python3 "$ROOT/tests/eval/localize/mrpt_selftest/run_selftest.py" >"$WORK/mrpt_selftest.log" 2>&1; then
    mrpt_ok=1
  else
    echo "bench localize: the MRPT self-test failed ($WORK/mrpt_selftest.log): no MRPT figures" >&2
  fi
fi
if [ "$mrpt_ok" = 1 ]; then
  # The worlds benched: world_args holds "--sim NAME=PATH" pairs (nav_worlds.sh keeps its list
  # to itself).
  for spec in "${world_args[@]}"; do
    [ "$spec" = --sim ] && continue
    name="${spec%%=*}"
    python3 "$ROOT/deploy/bench/mrpt/mrpt_localize.py" "$WORK/$name/mrpt" --out "$WORK/$name/mrpt/mrpt.json" ||
      echo "bench localize: MRPT failed on $name" >&2
  done
fi
python3 - "$JSON.rgnav" "$JSON" "$WORK" <<'PY'
import json, math, os, sys
src, dst, work = sys.argv[1:4]
j = json.load(open(src))
se, n, ok, trials = 0.0, 0, 0, 0
j["mrpt"] = {}
for name in j.get("worlds", {}):
    path = os.path.join(work, name, "mrpt", "mrpt.json")
    if not os.path.exists(path):
        continue
    m = json.load(open(path))
    j["mrpt"][name] = {"tracking": m.get("tracking"), "global": m.get("global")}
    t = m.get("tracking") or {}
    if t.get("rmse_m") is not None and t.get("steps"):
        se += t["rmse_m"] ** 2 * t["steps"]
        n += t["steps"]
    g = m.get("global") or {}
    if g.get("trials"):
        ok += round(g.get("success_ratio", 0) * g["trials"])
        trials += g["trials"]
j["mrpt_tracking_rmse_m"] = math.sqrt(se / n) if n else None
j["mrpt_global_trials"] = trials
j["mrpt_global_success_ratio"] = ok / trials if trials else None
json.dump(j, open(dst, "w"), indent=2)
os.remove(src)
print(json.dumps({k: v for k, v in j.items() if not isinstance(v, dict)}, indent=2))
PY
