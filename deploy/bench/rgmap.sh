#!/usr/bin/env bash
# ./rgnav bench rgmap: evaluation of RG maps (dissertation 6.1, Table 6.1) built by the offline
# pipeline (scan mapper + gateway detector + RG kernel, rgnav_rgmap_offline's code) with the
# configs of config/. Writes logs/bench/rgmap.json; maps and pictures under logs/bench/rgmap/<name>/
# (with truth_pairs.txt: the true pose and the scan mapper's final estimate at every accepted scan).
#
# worlds.<name> — simulated tour (lock-step simulator, config/sim.yaml odometry error and laser,
#   one lap of a closed tour entering every reachable labelled room; walking people left out, the
#   tour follower does not avoid them): office.yaml and every IPA building map (10 plain and their
#   10 furnished versions), exact ground truth. The map
#   is placed in the world by the rigid fit of the accepted scans' estimates to their true poses.
#   seg_precision / seg_recall: Bormann et al. 2016 as their evaluation code computes the paper's
#     figures (ipa_room_segmentation EvaluationSegmentation, "micro" values) — per region the share
#     of its freespace cells (0.05 m) in its best-overlapping room, per room the share of its
#     explored cells covered by its best region, unweighted means over regions / rooms; regions
#     and rooms of <= 0.25 m^2 (100 pixels at 0.05 m) left out, as there. Differences left (an RG
#     map is no partition): regions overlap, and cells outside every room are not counted in a
#     region's size (procs/rg_kernel/tools/rgmap_metrics.h); seg_recall_full: over whole rooms
#     (unexplored = missed);
#     seg_jaccard: mean best IoU per room; seg_coverage: share of room cells in some region.
#   seg_loss_seen_through / seg_loss_driven_through: 1 - seg_precision split by cause (they add up to
#     it): region cells outside the region's best room in rooms its robot never stood in (seen
#     through an opening) / in rooms where it stood (a missed gateway or a merge joined the rooms).
#     Per region with rgnav_rgmap_bench --diagnose (tests/eval/rgmap/segmentation_diagnosis.h).
#   over_segmented_rooms / under_segmented_regions: rooms split by >= 2 regions each holding
#     >= 20 % of the room / regions spanning >= 2 rooms each >= 20 % of the region.
#   gateways_truth / _matched / _missed / _false: RG map gateways (not neutralized; a crossing that
#     joins more than two regions is one gateway object per pair with the same outline, counted once) matched one to
#     one, nearest first, within gateway_match_m to ground-truth gateways between explored rooms
#     (world files: labelled gateways incl. hallway junctions; IPA maps: doorway runs closed in
#     *_gt_segmentation.png); gateways_crossed(_matched): only those the true path went through.
#   graph_isomorphic: region graph (live regions, traversed non-neutralized gateways; a crossing joins
#     every pair of its regions, as the truth's crossings do) isomorphic to
#     the room graph of the tour's rooms; graph_*: node/edge counts and differences, edges
#     matched / missing / extra / internal under the region -> best room mapping.
#   regions, merged_regions, gateways, doors, neutralized, segments, compression (scan points /
#     segment end points), mean_region_bytes (freespace bitmap + segments), consistency_problems,
#     overlapping_regions (pairs of regions, the smaller with half its freespace in the other's:
#     one place mapped twice, or a small room seen whole through a wide opening).
#   ghost_segments / ghost_segment_m: line-map segments (of live regions) with nothing static of the
#     world within 0.1 m — more than half of the segment's length farther than that from every wall,
#     door leaf (open or closed), box and table leg at the laser's height, in the world frame after
#     the rigid fit (tests/eval/rgmap/ghost_segments.h): what moved, left in the map; and their length.
#     Walls the map holds more than 0.1 m off after the fit (SLAM drift) count too: the figure of a
#     world without people, and of the true-pose runs, tells them apart.
#   people: walking people kept in the world (0: left out).
# worlds.office_people — office.yaml driven with its walking people (the same tour: they and the
#   robot pass through each other, as the tour follower has no obstacle avoidance); the same keys.
# ghost_segments — issue 33's figure: ghost segments summed over the worlds driven with people
#   (scan mapper poses; ghost_segments_segments: all their segments, for scale;
#   ghost_segment_worlds: per world).
# worlds.rand_<seed>, rand_<seed>_furnished — generated buildings (issue 33; tests/eval/buildings,
#   rgnav_building_gen: hallways straight, L, T, crossing or a ring, 1.2-3.5 m wide, offices to
#   open halls, doors 0.8-1.6 m and openings 2-3 m, rooms behind rooms, walls 1-4 px with scan
#   noise; the furnished variant with tables and chairs by their legs, cabinets, clutter), the
#   same keys plus "random_building": true. RANDOM_BUILDINGS of them (default 50; 0: none), seeds
#   RANDOM_SEED (default 1) on, written to <RGMAP_WORK>/random/; RANDOM_VARIANTS (default
#   "plain furnished") which maps of each are driven.
# summary.<worlds|worlds_true_poses>.<ipa_plain|ipa_furnished|random_plain|random_furnished> —
#   means of seg_precision / seg_recall over the maps (Bormann et al. report means over their
#   maps), gateway sums (gateways_crossed(_matched) too), isomorphic count, failed runs (left out
#   of the means), broken_maps, and doorways_crossed_gateway_ratio (crossed doorways that became
#   gateways / crossed doorways), false_gateway_ratio (false / reported gateways),
#   isomorphic_ratio (isomorphic / worlds run); the IPA groups also the Voronoi method's figures.
# random_buildings — generated buildings driven; broken_maps / broken_map_list — worlds (named and
#   generated, scan mapper poses) whose map is broken: alignment_rmse_m > 0.3 m (name -> RMSE).
# logs.<name> — corrected real logs of ../shared/data/laser/corrected (poses taken as given, as
#   the dissertation did); no ground truth: counts only (false_positives is null).
#   gateways, doors, neutralized, not_traversed (Table 6.1 columns), regions, merged_regions,
#   segments, scan_points, compression, mean_region_bytes, consistency_problems, overlapping_regions.
# worlds_true_poses.<name> — the same keys, the same tour mapped on the simulator's true poses
#   instead of the scan mapper's (poses: "true"): segmentation errors apart from SLAM errors.
#   Diagnostic only; the headline (worlds.<name>) is on the scan mapper's poses. Pictures under
#   logs/bench/rgmap/<name>/true_poses/.
# Env: RGMAP_SIM_MAX_S caps simulated seconds per world (default 2400: office_g's 742 m tour
#   takes 1550 s); RGMAP_JSON and RGMAP_WORK write elsewhere (default logs/bench/rgmap.json,
#   logs/bench/rgmap/); RGMAP_ONLY (space-separated names, e.g. "office lab_ipa") runs only those
#   worlds and no real log unless named ("random": all generated buildings); RGMAP_TRUE_POSES=0 leaves out the true-pose runs;
#   RGMAP_RG_CONFIG runs another RG kernel config (default config/rg_kernel.yaml), e.g. one with a
#   rule switched off: build/bin/config_overlay config/rg_kernel.yaml OFF.yaml kernel.door_exits=false.
# The benchmark itself: tests/eval/rgmap (rgnav_rgmap_bench).
# shellcheck source=lib/bench_env.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/bench_env.sh"
IPA="$SHARED/maps/ipa"
JSON="${RGMAP_JSON:-$ROOT/logs/bench/rgmap.json}"
WORK="${RGMAP_WORK:-$ROOT/logs/bench/rgmap}"
ONLY="${RGMAP_ONLY:-}"
wanted() { [ -z "$ONLY" ] || [[ " $ONLY " == *" $1 "* ]]; }
bench_binary rgnav_rgmap_bench rgmap "it needs drivers/sim, scan_mapper, gateway_detector"
mkdir -p "$WORK"
reals=()
for name in intel freiburg-079 belgioioso aces; do
  log="$SHARED/laser/corrected/$name-corrected.log.gz"
  [ -f "$log" ] && wanted "$name" || continue
  "$BUILD/bin/rgnav_import" "$log" "$WORK/$name.lcmlog" >/dev/null
  reals+=(--real "$name=$WORK/$name.lcmlog")
done
# Every building map of ../shared/data/maps/ipa, plain and furnished (<name>_furnished), named
# after its image without "_scan".
specs=("office=$ROOT/config/worlds/office.yaml")
for png in "$IPA"/*.png; do
  stem=$(basename "$png" .png)
  [[ "$stem" == *_gt_segmentation || "$stem" == *_furnitures ]] && continue
  name=${stem%_scan}
  specs+=("$name=$png")
  [ -f "$IPA/${stem}_furnitures.png" ] && specs+=("${name}_furnished=$IPA/${stem}_furnitures.png")
done
sims=()
for spec in "${specs[@]}"; do
  wanted "${spec%%=*}" && sims+=(--sim "$spec")
done
# The office world again with its walking people (ghost_segments).
wanted office_people && sims+=(--sim-people "office_people=$ROOT/config/worlds/office.yaml")
# Generated buildings (tests/eval/buildings): no rule was fitted to them.
add_random_buildings sims "$WORK/random" "${RANDOM_VARIANTS:-plain furnished}" "$ONLY"
flags=()
[ "${RGMAP_TRUE_POSES:-1}" = 0 ] || flags+=(--true-poses)
exec "$bin" --config "$ROOT/config/scan_mapper.yaml" --gateway-config "$ROOT/config/gateway_detector_aligned.yaml" \
  --rg-config "${RGMAP_RG_CONFIG:-$ROOT/config/rg_kernel.yaml}" --sim-config "$ROOT/config/sim.yaml" \
  --json "$JSON" --out "$WORK" --laps 1 --max-sim-s "${RGMAP_SIM_MAX_S:-2400}" \
  "${flags[@]}" "${sims[@]}" "${reals[@]}"
