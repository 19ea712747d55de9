#!/usr/bin/env bash
# ./rgnav bench rgmap: evaluation of RG maps (dissertation 6.1, Table 6.1) built by the offline
# pipeline (scan mapper + gateway detector + RG kernel, rgnav_rgmap_offline's code) with the
# configs of config/. Writes logs/bench/rgmap.json; maps and pictures under logs/bench/rgmap/<name>/.
#
# worlds.<name> — simulated tour (lock-step simulator, config/sim.yaml odometry error and laser,
#   one lap of a closed tour entering every reachable labelled room; walking people left out, the
#   tour follower does not avoid them): office.yaml and IPA building maps (plain and furnished),
#   exact ground truth. The map
#   is placed in the world by the rigid fit of the accepted scans' estimates to their true poses.
#   seg_precision / seg_recall: Bormann et al. 2016 — per region the share of its freespace cells
#     (0.05 m) in its best-overlapping room, per room the share of its explored cells covered by
#     its best region, unweighted means; seg_recall_full: over whole rooms (unexplored = missed);
#     seg_jaccard: mean best IoU per room; seg_coverage: share of room cells in some region.
#   seg_loss_seen_through / seg_loss_driven_through: 1 - seg_precision split by cause (they add up to
#     it): region cells outside the region's best room in rooms its robot never stood in (seen
#     through an opening) / in rooms where it stood (a missed gateway or a merge joined the rooms).
#     Per region with rgnav_rgmap_bench --diagnose (procs/rg_kernel/tools/segmentation_diagnosis.h).
#   over_segmented_rooms / under_segmented_regions: rooms split by >= 2 regions each holding
#     >= 20 % of the room / regions spanning >= 2 rooms each >= 20 % of the region.
#   gateways_truth / _matched / _missed / _false: RG map gateways (not neutralized) matched one to
#     one, nearest first, within gateway_match_m to ground-truth gateways between explored rooms
#     (world files: labelled gateways incl. hallway junctions; IPA maps: doorway runs closed in
#     *_gt_segmentation.png); gateways_crossed(_matched): only those the true path went through.
#   graph_isomorphic: region graph (live regions, traversed non-neutralized gateways) isomorphic to
#     the room graph of the tour's rooms; graph_*: node/edge counts and differences, edges
#     matched / missing / extra / internal under the region -> best room mapping.
#   regions, merged_regions, gateways, doors, neutralized, segments, compression (scan points /
#     segment end points), mean_region_bytes (freespace bitmap + segments), consistency_problems.
# logs.<name> — corrected real logs of ../shared/data/laser/corrected (poses taken as given, as
#   the dissertation did); no ground truth: counts only (false_positives is null).
#   gateways, doors, neutralized, not_traversed (Table 6.1 columns), regions, merged_regions,
#   segments, scan_points, compression, mean_region_bytes, consistency_problems.
# Env: RGMAP_SIM_MAX_S caps simulated seconds per world (default 1200).
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
SHARED="${RGNAV_DATA:-$ROOT/../shared/data}"
IPA="$SHARED/maps/ipa"
OUT="$ROOT/logs/bench"
WORK="$OUT/rgmap"
bin="$BUILD/bin/rgnav_rgmap_bench"
if [ ! -x "$bin" ]; then
  echo "bench rgmap: $bin is not built (it needs drivers/sim, scan_mapper, gateway_detector)" >&2
  exit 1
fi
mkdir -p "$WORK"
reals=()
for name in intel freiburg-079 belgioioso aces; do
  log="$SHARED/laser/corrected/$name-corrected.log.gz"
  [ -f "$log" ] || continue
  "$BUILD/bin/rgnav_import" "$log" "$WORK/$name.lcmlog" >/dev/null
  reals+=(--real "$name=$WORK/$name.lcmlog")
done
exec "$bin" --config "$ROOT/config/scan_mapper.yaml" --gateway-config "$ROOT/config/gateway_detector_aligned.yaml" \
  --rg-config "$ROOT/config/rg_kernel.yaml" --sim-config "$ROOT/config/sim.yaml" \
  --json "$OUT/rgmap.json" --out "$WORK" --laps 1 --max-sim-s "${RGMAP_SIM_MAX_S:-1200}" \
  --sim "office=$ROOT/config/worlds/office.yaml" \
  --sim "lab_ipa=$IPA/lab_ipa.png" \
  --sim "office_e=$IPA/office_e.png" \
  --sim "lab_intel=$IPA/lab_intel.png" \
  --sim "lab_intel_furnished=$IPA/lab_intel_furnitures.png" \
  --sim "office_e_furnished=$IPA/office_e_furnitures.png" \
  "${reals[@]}"
