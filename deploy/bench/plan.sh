#!/usr/bin/env bash
# ./rgnav bench plan: the planner (procs/planner) on RG maps built by rgnav's own pipeline (scan
# mapper + gateway detector + RG kernel, one lap of each world's tour, as ./rgnav bench localize
# maps them). Writes logs/bench/plan.json; maps, per-world JSON and routes.png under
# logs/bench/plan/<world>/. Figures are reported, never asserted; `targets` lists the issue's.
#
# Planning alone, per world PLAN_PAIRS random start/goal pairs (default 250) of standable points
# (RegionPlanner::standable) in random live regions, planned by GlobalPlanner::plan, against one
# whole-building grid composed from the same RG map in the map frame (every live region through
# its map_from_region: freespace free, line segments occupied, the rest unknown; 0.05 m whatever
# the planner's own grids, --reference-resolution) and its configuration space (cells at least the
# robot radius from anything not free):
#   The whole grid also has the gateways' openings free as the planner carves them, and one-cell
#   seams of unknown between free cells (where two regions' bitmaps meet) free; start and goal
#   move up to adapt_distance onto free cells joined to the other end.
#   pairs, reference_paths (the reference found a path: "a path exists"), success_ratio = rgnav
#     routes / pairs where a path exists; failures_where_a_path_exists, no_path_both,
#     routes_where_reference_has_none; route_defects (legs that do not join, miss start or goal,
#     lengths that disagree) and routes_in_collision (passing a cell more than a cell inside the
#     robot radius on the whole grid, ends within adapt_distance left out); `failures` lists the
#     first few per kind with their points (region frame and map frame) for reproduction:
#     no_route, route_without_reference, route_defect, route_near_wall, long_route (> 1.5 x the
#     reference), target_spacing, target_line_near_wall, warm_cold_disagree.
#   global_ms_*: PlanStats::global_ms of a "cold" plan (the planner's cached region paths dropped
#     before each request by a new map version, so every region path the route needs is planned);
#     plan_ms_* = global + region ms of the cold plan, plan_wall_ms_* its wall time,
#     plan_warm_wall_ms_* one planner meeting the pairs in turn (cache kept).
#   region_ms_p50/p99: RegionPlanner::plan timed alone on --region-pairs pairs of points inside one
#     region; region_path_length_ratio_*: those paths against the whole grid's shortest.
#   length_ratio_*: route length (legs + gaps where they meet) / the reference length. The
#     reference is the exact shortest on the same occupancy: 16-connected A* then string pulling
#     with line of sight on the configuration space, turns cut to the obstacles. The detour split
#     in two: length_ratio_legs_* = the legs / each leg's own shortest path between its ends in
#     its region and the regions beside it (the region paths' share), graph_ratio_* = those
#     summed / the reference (the RG graph's share: its crossing points, and regions the whole
#     grid joins where the map has no gateway).
#   clearance_min_m: smallest RouteLeg::min_clearance over all routes; clearance_sampled_*: the
#     whole grid's clearance sampled along the routes (min, mean of the per-route means);
#     clearance_where_it_fits_ratio: of the pairs joined by cells of clearance >= radius + margin
#     (ends within 1 m), the share of routes keeping that clearance (less one cell) away from 1 m of
#     their ends.
#   grid_astar_ms_*: the baseline NavFn-style planners use, 8-connected A* on the same whole grid
#     with the planner's wall cost, unquantised (costmap built once, not timed);
#     grid_astar_length_ratio_* its length over the reference; grid_dijkstra_ms_p50 the same
#     search without the heuristic (NavFn's wavefront); speedup_vs_grid = grid_astar_ms_p50 /
#     plan_ms_p50 (speedup_vs_grid_wall with the cold wall time).
#   target_spacing_*: the targets cut_targets() gives over every route (config spacing);
#     target_segments_near_walls: straight lines between targets nearer than radius - 0.1 m to a
#     wall; targets_not_reaching_goal.
# Closed loop (worlds in PLAN_CLOSED_LOOP, default office lab_ipa office_e; "": none): the
# simulator, collision avoidance and the lld in lock-step at 20 Hz with walking people (a world
# without people gets three walkers that wait for the robot and step round it), the Planner fed
# the true pose in a region (a perfect localizer that hands over between regions as the
# localizer does and, where no neighbour holds the place, takes the region that does) and
# collision avoidance's blocked/reactive mode (yielding to a person is neither); PLAN_GOALS goals (default 100)
# one after another from where the last ended:
#   goals are where the robot's body fits in the true world (goals_out_of_reach_skipped: under a
#   table top the laser passes beneath); closed_loop_goals, closed_loop_success_ratio (REACHED
#   and truly within 0.5 m); a goal not reached by its timeout (3 x the longer of the reference
#   and the planner's first route, at max speed, + 60 s: a detour the RG graph forces costs SPL,
#   not success) counts as no_path if the planner says NO_PATH then (it keeps such a goal and
#   plans it again when a closed mark expires), else timeouts; goals_with_a_no_path_report;
#   closed_loop_collisions (simulator contacts) and collisions_with (by kind); spl = mean over
#   goals of success x shortest / max(shortest, driven), shortest = the reference between the
#   true start and goal (map frame through the truth frames); replans (per goal, summed),
#   time_ratio_p50 (time / shortest at max speed), planner_cpu_share; goal_log per world.
#   door cases (PLAN_DOOR_CASES per world, default 2): a door or narrow-passage gateway of the map
#   closed by a door leaf in the simulated world (reopening after 90 s), the robot sent from
#   1.5-6 m before it into the smaller region behind it: as_expected when, with another way round
#   (way_round_exists: through the map's other gateways, and free on the whole grid with the leaf
#   drawn in), the robot arrives before the door reopens without a NO_PATH; without one, NO_PATH
#   comes before the door reopens and the robot gets through afterwards; no collision either way.
#   door_case_log per world has the times and the planner's reports.
# Env: PLAN_ONLY (space-separated world names) runs only those; PLAN_PAIRS, PLAN_GOALS,
#   PLAN_DOOR_CASES, PLAN_CLOSED_LOOP; PLAN_ARGS adds bench flags (e.g. "--region-pairs 100
#   --seed 3"); PLAN_TRACE=1 prints a line per second (pose, region, collision avoidance's mode,
#   the next targets, the nearest person and wall, the planner's status) and per goal of the
#   closed loop to stderr.
#   Quick run: PLAN_ONLY=office PLAN_PAIRS=50 PLAN_GOALS=5 ./rgnav bench plan
# The benchmark itself: tests/eval/plan (rgnav_plan_bench).
# shellcheck source=lib/bench_env.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/bench_env.sh"
JSON="$ROOT/logs/bench/plan.json"
WORK="$ROOT/logs/bench/plan"
ONLY="${PLAN_ONLY:-}"
# shellcheck source=lib/nav_worlds.sh
source "$ROOT/deploy/bench/lib/nav_worlds.sh"
bench_binary rgnav_plan_bench plan
# The localization benchmark's worlds.
nav_world_args
args=("${world_args[@]}")
for name in ${PLAN_CLOSED_LOOP-office lab_ipa office_e}; do
  wanted "$name" && args+=(--closed-loop "$name")
done
mkdir -p "$WORK"
# shellcheck disable=SC2086
exec "$bin" --json "$JSON" --out "$WORK" "${args[@]}" --pairs "${PLAN_PAIRS:-250}" --goals "${PLAN_GOALS:-100}" \
  --door-cases "${PLAN_DOOR_CASES:-2}" ${PLAN_ARGS:-}
