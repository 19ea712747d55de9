#!/usr/bin/env bash
# ./rgnav bench explore: the explorer (procs/explorer) with the planner exploring simulated
# buildings by itself, beside a frontier explorer (the baseline) in the same simulator. Writes
# logs/bench/explore.json; per world logs/bench/explore/<world>/explore.json and the explored RG maps
# (<start>_<method>/rgmap.png, ...). Figures are reported, never asserted; `targets` lists the issue's.
#
# In-process, lock-step at 20 Hz and deterministic with --seed (tests/eval/explore/explore_run.h):
# the simulated B21r (ray-cast laser, drifting odometry, walking people: the world's own, or three
# walkers pacing the tour that wait for the robot and step round it, as ./rgnav bench plan has them)
# with collision avoidance and the lld follower; scans and odometry into the RG mapping pipeline
# (scan mapper, gateway detector, RG kernel) as the live processes get them. rgnav: the explorer gets
# the RG map (copied when its version changed, at most once a second, as RG_MAP arrives), the SLAM
# pose (the scan mapper's estimate of its newest accepted scan composed with odometry since, map
# frame), each accepted scan's gateway hypotheses (through GATEWAY_HYPOTHESES' conversion) and the
# planner's goal status; its NAV_GOALs go to the planner (posed in the map's current region), the
# planner's TARGETS to collision avoidance. Collision avoidance also hears what the vision would
# give it (OBSTACLES_3D) of solids the laser misses — table tops — from ground truth: what falls in
# the fixed stereo head's field of view within its range, remembered as its OctoMap keeps it
# (tests/eval/explore/vision_stand_in.h; the real vision in the loop would make each run several
# times slower, ./rgnav bench vision measures it); EXPLORE_ARGS=--laser-only runs without it.
# frontier: Yamauchi 1997 / explore_lite, nearest frontier first on a 0.1 m log-odds grid of the
# accepted scans at the SLAM poses, clusters >= the robot's width, goal = the frontier cell nearest by breadth-first search over cells the robot fits in,
# grid A* with a wall cost (unknown as free) cut into targets for the same collision avoidance
# (tests/eval/explore/frontier_explorer.h).
#
# Worlds: the office world and four IPA building maps (as ./rgnav bench plan: a lab, an institute
# floor, a furnished lab, an office floor). Starts: the world's own ("fixed") and EXPLORE_STARTS
# random ones (default 1) where the robot stands with 0.3 m to spare, reachable from the fixed one.
# A run ends when the explorer says it is done, or at its cap (a timeout): cap_factor (6) x the
# ground-truth tour's time at 0.5 m/s, at least 600 s, at most --max-sim-s (3600 s).
#
# Top level (worst over worlds and starts, rgnav's explorer):
#   worlds               per world: tour (the ground-truth tour from the fixed start: length_m,
#                        rooms, seg_precision/recall of the map it drives, as ./rgnav bench rgmap),
#                        cap_s, people, reachable_free_m2, rgnav / frontier (the worst of its starts),
#                        runs (every run, with detail.driver: the explorer's status, goals by kind,
#                        NO_PATH reasons, stack entries set aside, CPU; detail.map: the rgmap bench's
#                        keys for the explored map), truth_s, runs_wall_s
#   rooms_entered_ratio  reachable ground-truth rooms (those the tour from that start enters) the
#                        robot's true position was inside at some time / reachable rooms
#   area_seen_ratio      reachable free area (cells where the body can be, robot radius around the
#                        places its centre can reach from the start) that some beam of the laser at
#                        its true pose passed or ended in (up to 8 m, the RG kernel's range)
#   premature_ends       runs that ended "done" with a reachable room not entered or < 90 % seen
#                        (max over worlds of the per-world count)
#   length_vs_frontier   driven length / the frontier explorer's from the same start (max)
#   length_vs_tour       driven length / the ground-truth tour's from the same start (max; the tour
#                        returns to its start, exploring need not)
#   seg_precision_delta  explored map's segmentation precision - the tour-driven map's (min)
#   frontier             the same keys for the baseline; totals: runs, premature ends, timeouts
#                        (runs at their cap), collisions per method; timing: wall seconds.
#   Per run also: time_to_90_s (90 % of the reachable free area seen), time_s, driven_m,
#   collisions (+ contacts), timed_out, ended_done, rooms_missed, seg_precision/recall.
# Env: EXPLORE_ONLY (space-separated world names) runs only those; EXPLORE_STARTS random starts per
#   world; EXPLORE_METHODS ("rgnav frontier"); EXPLORE_SPIN=S: the robot first turns on the spot S
#   seconds (0.5 rad/s) before the explorer takes over (default 0; the explorer itself looks
#   behind first, config/explorer.yaml recovery.look_at_start); EXPLORE_JOBS runs at once (default 2); EXPLORE_ARGS adds bench flags
#   (e.g. "--seed 3 --max-sim-s 1800"); EXPLORE_TRACE=1 prints a line per simulated second per run
#   (true and SLAM pose, collision avoidance's mode, the nearest person's distance, area seen, rooms, the explorer's phase,
#   activity, region, completeness, stack, goal and the planner's status and route) and every goal
#   sent and ended with the planner's reason, to stderr. EXPLORE_DUMP_NO_PATH=DIR writes every goal the planner
#   found no path for, with the map and pose it planned on, to DIR (replay: build/bin/rgnav_plan_replay).
#   Quick run: EXPLORE_ONLY=lab_ipa EXPLORE_STARTS=0 ./rgnav bench explore
# Time (2 cores, --jobs 2): 8-9 minutes for the full run (2026-12: 490 s wall, 20 runs, every one
#   ending "done" before its cap); runs simulate at ~13x real time (collision avoidance's trajectory
#   search dominates), so runs going to their caps would take up to ~20 minutes.
# The benchmark itself: tests/eval/explore (rgnav_explore_bench).
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
JSON="$ROOT/logs/bench/explore.json"
WORK="$ROOT/logs/bench/explore"
ONLY="${EXPLORE_ONLY:-}"
# shellcheck source=lib/nav_worlds.sh
source "$ROOT/deploy/bench/lib/nav_worlds.sh"
bin="$BUILD/bin/rgnav_explore_bench"
[ -x "$bin" ] || { echo "bench explore: $bin is not built" >&2; exit 1; }
nav_world_args
[ ${#world_args[@]} -gt 0 ] || { echo "bench explore: no world left by EXPLORE_ONLY='$ONLY'" >&2; exit 2; }
methods=()
for m in ${EXPLORE_METHODS:-rgnav frontier}; do methods+=(--methods "$m"); done
mkdir -p "$WORK"
# shellcheck disable=SC2086
exec "$bin" --json "$JSON" --out "$WORK" "${world_args[@]}" "${methods[@]}" --starts "${EXPLORE_STARTS:-1}" \
  --spin-at-start "${EXPLORE_SPIN:-0}" --jobs "${EXPLORE_JOBS:-2}" ${EXPLORE_ARGS:-}
