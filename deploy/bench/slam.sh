#!/usr/bin/env bash
# ./rgnav bench slam: the scan mapper on the real raw logs of ../shared/data/laser/raw
# (Intel with raw odometry + reference poses from the corrected Intel log, Mines exp1/exp2,
# MIT CSAIL) with one parameter set (config/scan_mapper.yaml). Writes logs/bench/slam.json and
# maps/trajectories under logs/bench/slam/<log>/ (with reference_pairs.txt: reference and
# estimate at every scan with a reference pose; sim_<map>/truth_pairs.txt: truth, final and
# online estimate (when the scan was added) at every accepted scan, and whether it closed a
# loop; sim_<map>/closures.txt: every loop closure of the final graph, its error at the true
# poses and the chi2 of that error; deploy/tools/truth_pairs_errors.py and
# reference_pair_errors.py read the pairs). Scans the mapper did not accept are registered between their
# accepted neighbours for the reference comparison (offline_mapping.cpp).
# Simulated part (sim.*, exact ground truth): the lock-step simulator (drivers/sim, odometry
# error and laser of config/sim.yaml) drives two laps of a closed tour through six IPA building
# maps (lab_a: rows of equal cubicles; office_c: equal rooms with round bays, its door at the
# bay's centre, where a 180 deg scan sees only the arc) and the built-in office world (the
# demo's; its people left out: the bench's tour follower cannot pass them), feeding its scans
# and odometry straight into the mapping library;
# office_people is the office again with its four people walking (hallways and lobby; the
# robot's body passes through them, so the tour is the same): legs that move in the scans, the
# live demo's situation (config registration.moving_points). Relations metric
# (Kuemmerle et al.) and ATE against the true poses. Each world is capped at SLAM_SIM_MAX_S
# simulated seconds (default 1800); a capped run says so ("capped": true) in the JSON.
# loop_closures_wrong / loop_closures_inconsistent (worlds): closures of the final graph more than
# 0.1 m off the true relative pose / with a chi2 at the true poses above max_residual_chi2.
# loop_pruned: earlier closures taken out once later ones showed them inconsistent.
# odometry_trans_scale (every log and world): the scale on config odometry_noise's translation
# sigmas that the scan mapper learned from its matches (1: the odometry is as good as configured).
# Every world is also driven with each simulator seed of SLAM_SIM_SEEDS (default 1,2,3; "" for
# none): sim_seeds.<map> holds the figures per seed, their mean and the worst, since one seed's
# odometry noise can hide or provoke an error (sim.<map> stays the config's seed).
# Generated buildings (issue 33; tests/eval/buildings, rgnav_building_gen; ./rgnav bench rgmap
# describes them): sim.rand_<seed> (and rand_<seed>_furnished), driven as the named worlds but with
# the config's seed only, "random_building": true. RANDOM_BUILDINGS of them (default 50; 0: none),
# seeds RANDOM_SEED (default 1) on, written to logs/bench/slam/random/; SLAM_RANDOM_VARIANTS
# (default "plain"; "plain furnished" adds the furnished maps, which the rgmap bench drives too).
# Top level: random_buildings; broken_maps / broken_map_list: simulated runs (sim.*, named and
# generated) whose map is broken, ate_rmse_m (the rigid-fit RMSE) > 0.3 m (name -> RMSE).
# SLAM_ONLY (space-separated names of logs and worlds, "random" for every generated building)
# runs only those; SLAM_JSON writes the JSON elsewhere (default logs/bench/slam.json).
# The benchmark itself: tests/eval/slam (rgnav_slam_bench).
# shellcheck source=lib/bench_env.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/bench_env.sh"
DATA="$SHARED/laser"
IPA="$SHARED/maps/ipa"
OUT="$ROOT/logs/bench"
WORK="$OUT/slam"
mkdir -p "$WORK"
imp="$BUILD/bin/rgnav_import"
ONLY="${SLAM_ONLY:-}"
wanted() { [ -z "$ONLY" ] || [[ " $ONLY " == *" $1 "* ]]; }
args=()
# The raw Intel log was decoded from an MRPT rawlog, which spreads its 180 beams over 180 deg
# inclusive; the scanner's geometry is CARMEN's (the log came from CARMEN): [-90, 89] deg at
# 1 deg. The published corrected poses fit that geometry best (the share of end points within
# 2 cm of another scan's, over the 173 reference scans: 0.640, against 0.593 inclusive, 0.601
# half a beam and 0.53 / 0.51 a beam off; deploy/tools/reference_consistency.py), and so does
# the scan mapper's own map (consistency 0.906 -> 0.925 imported without --fov-inclusive).
if wanted intel; then
  "$imp" "$DATA/raw/intel/intel-raw-odometry.carmen.log.gz" "$WORK/intel.lcmlog" --odometry-delay-scans 1 \
    --reference-from "$DATA/corrected/intel-corrected.log.gz"
fi
wanted mines_exp1 && "$imp" "$DATA/raw/mines/exp1.dat" "$WORK/mines_exp1.lcmlog"
wanted mines_exp2 && "$imp" "$DATA/raw/mines/exp2.dat" "$WORK/mines_exp2.lcmlog"
wanted csail && "$imp" "$DATA/raw/csail/csail-robotlaser.log.gz" "$WORK/csail.lcmlog"
# Laser mounting poses are properties of the robots that recorded the logs, not tuning: the
# Intel and CSAIL logs give scans in the robot frame; the Mines rover's URG sits 145 mm ahead
# of the axle (BreezySLAM examples/mines.py, offset_mm=145). The raw Intel log's timestamps
# are synthetic (194 s for every 5th scan of a 2691 s recording, Hess et al. 2016 Table V):
# "#2691": realtime_factor is taken on the recording's true duration (as Hess et al. take
# theirs); realtime_factor_synthetic_timestamps on the 194 s the timestamps span.
for spec in "intel=$WORK/intel.lcmlog@0,0,0#2691" "mines_exp1=$WORK/mines_exp1.lcmlog@0.145,0,0" \
            "mines_exp2=$WORK/mines_exp2.lcmlog@0.145,0,0" "csail=$WORK/csail.lcmlog@0,0,0"; do
  wanted "${spec%%=*}" && args+=(--real "$spec")
done
for spec in "Freiburg79_scan=$IPA/Freiburg79_scan.png" "lab_intel=$IPA/lab_intel.png" "lab_ipa=$IPA/lab_ipa.png" \
            "office_e=$IPA/office_e.png" "lab_a=$IPA/lab_a_scan.png" "office_c=$IPA/office_c.png" \
            "office=$ROOT/config/worlds/office.yaml"; do
  wanted "${spec%%=*}" && args+=(--sim "$spec")
done
wanted office_people && args+=(--sim-people "office_people=$ROOT/config/worlds/office.yaml")
# Generated buildings (tests/eval/buildings): no rule was fitted to them.
add_random_buildings args "$WORK/random" "${SLAM_RANDOM_VARIANTS:-plain}" "$ONLY"
"$BUILD/bin/rgnav_slam_bench" --config "$ROOT/config/scan_mapper.yaml" --json "${SLAM_JSON:-$OUT/slam.json}" --maps "$WORK" \
  --sim-config "$ROOT/config/sim.yaml" --sim-laps 2 --sim-max-s "${SLAM_SIM_MAX_S:-1800}" \
  --sim-seeds "${SLAM_SIM_SEEDS-1,2,3}" "${args[@]}"
echo "wrote ${SLAM_JSON:-$OUT/slam.json}" >&2
