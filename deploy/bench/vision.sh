#!/usr/bin/env bash
# ./rgnav bench vision — the vision process (procs/vision): dense stereo, 3D rectangles, doors.
# Writes its keys into logs/bench/vision.json (other keys already there are kept); each part's
# own output goes to logs/bench/vision/{stereo,rectangles,doors}.json.
#   aloe_bad_pixel_ratio: StereoSGBM with config/vision.yaml's settings at full scale on the
#     Middlebury Aloe pair (../shared/data/stereo/aloe): share of the pixels with ground truth whose
#     disparity is missing or off by more than 1 px (aloe_bad_pixel_threshold_px); the ground truth
#     PNG holds the disparity in pixels (0 = unknown; aloe_scale_check = median estimate / truth
#     confirms the scale); also at 2 px, among estimated pixels only, and the density.
#   frame_ms_p50/p90: per frame of the simulated head (640x480, JPEG): decode + rectify + SGBM +
#     points + OctoMap insertion + column projection (+ the 3D rectangles every third frame), one
#     core, wall clock; stages in frame_stage_ms_p50 (rectangles: over the frames that ran them).
#   frame_cpu_ms_p50/p90: the same frames in the thread's CPU time: what a frame costs one core
#     whatever else the machine runs (the wall-clock figures grow with the machine's load).
#   octomap_points_per_s: points given to OctoMap's insertPointCloud per second spent in it.
#   grid_* and table_top_occupied_ratio: the grid against the rendered ground truth (see
#     tests/eval/vision/vision_bench_main.cpp).
#   rect_poses, rect_within_10cm_ratio: rgnav_rect_bench (tests/eval/vision/rect_bench_main.cpp): the
#     dissertation's 1000-pose experiment (3.3.4.1) with the refined fit; under rectangles/ also
#     the vanishing-line method alone, random views of doors, whiteboards and monitors with
#     stereo noise, and the whole detector on rendered views of the office world's doors
#     (rectangles.rendered_doors) and of its whiteboards and posters with the kind the vision
#     gives the ones found (rectangles.rendered_wall_objects: whiteboards.found_ratio,
#     whiteboards.called_whiteboard_ratio_of_found, posters.called_whiteboard, ...).
#   door_precision_laser, door_precision_vision, door_recall_vision: the gateway bench's door
#     evaluation alone (gateway_bench --only none): one drive of the office world's tour, a
#     detector on the laser and one that also gets the simulated head's rectangles (2 Hz).
#   courses, collisions_vision_off, collisions_vision_on (and reached_vision_off/on): rgnav_vision_courses
#     (tests/eval/vision/vision_courses_main.cpp): generated furnished rooms (tables whose tops the
#     laser misses, pedestal chairs, wall shelves), each driven by collision avoidance + lld around
#     the simulator twice in the same run, without and with the vision's grid (the head rendered in
#     lock-step at stereo_capture's rate); a collision is the robot body meeting any solid up to its
#     height. The rest of its output under obstacle_courses; per course in
#     logs/bench/vision/courses.json, with what the grid showed of each solid hit with vision on
#     (vision_on_contacts_in_grid: grids_marking 0 = never in the grid, cells_now 0 = not in the
#     grid collision avoidance had at the contact).
#   calib_reprojection_px: rgnav_stereo_calibrate on the shared chessboard pairs (9x6 inner corners,
#     25 mm squares assumed): cv::stereoCalibrate's RMS reprojection error; the file it writes is
#     the one checked in as config/stereo/chessboard_demo.yml.
# VISION_ARGS adds flags to rgnav_vision_bench (e.g. "--frames 40 --approaches 5 --pictures DIR"),
# RECT_ARGS to rgnav_rect_bench, COURSES_ARGS to rgnav_vision_courses (e.g. "--courses 5"; "--parts 2 --part I" drives
# every second course, for two runs side by side whose per_course lists merge);
# VISION_DOORS=0 skips the door evaluation (minutes), VISION_COURSES=0 the courses (~half an hour).
# The benchmarks: tests/eval/vision (rgnav_vision_bench, rgnav_rect_bench), tests/eval/gateways.
set -euo pipefail
ROOT="${RGNAV_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}"
BUILD="${RGNAV_BUILD:-$ROOT/build}"
BIN="$BUILD/bin/rgnav_vision_bench"
[[ -x "$BIN" ]] || { echo "vision.sh: $BIN not built (ninja -C $BUILD rgnav_vision_bench)" >&2; exit 1; }
OUT="$ROOT/logs/bench/vision"
mkdir -p "$OUT"
# One core: the figures are per core, and other work on the machine should not inflate them.
# shellcheck disable=SC2086
taskset -c 0 "$BIN" --out "$OUT/stereo.json" ${VISION_ARGS:-}
# shellcheck disable=SC2086
"$BUILD/bin/rgnav_rect_bench" ${RECT_ARGS:-} > "$OUT/rectangles.json"
if [[ "${VISION_DOORS:-1}" != 0 ]]; then
  "$BUILD/bin/gateway_bench" --config-dir "$ROOT/config" --only none --out "$OUT/doors.json"
fi
"$BUILD/bin/rgnav_stereo_calibrate" --out "$OUT/chessboard_demo.yml" --report "$OUT/calibration.json" >&2
if [[ "${VISION_COURSES:-1}" != 0 ]]; then
  # shellcheck disable=SC2086
  taskset -c 0 "$BUILD/bin/rgnav_vision_courses" --out "$OUT/courses.json" ${COURSES_ARGS:-}
fi
python3 - "$OUT" "$ROOT/logs/bench/vision.json" <<'PY'
import json, os, sys
out, whole = sys.argv[1], sys.argv[2]
merged = {}
if os.path.exists(whole):
    try:
        merged = json.load(open(whole))
    except ValueError:
        merged = {}
merged.update(json.load(open(os.path.join(out, "stereo.json"))))
rect = json.load(open(os.path.join(out, "rectangles.json")))
merged["rect_poses"] = rect["rect_poses"]
merged["rect_within_10cm_ratio"] = rect["rect_within_10cm_ratio"]
merged["rectangles"] = {k: rect[k] for k in ("dissertation", "random_views", "rendered_doors", "rendered_wall_objects") if k in rect}
doors_file = os.path.join(out, "doors.json")
if os.path.exists(doors_file):
    doors = json.load(open(doors_file))["doors"]
    merged["door_precision_laser"] = doors["laser_only"]["precision"]
    merged["door_recall_laser"] = doors["laser_only"]["recall"]
    if "precision" in doors.get("with_vision", {}):
        merged["door_precision_vision"] = doors["with_vision"]["precision"]
        merged["door_recall_vision"] = doors["with_vision"]["recall"]
    merged["doors"] = doors
calib = json.load(open(os.path.join(out, "calibration.json")))
merged["calib_reprojection_px"] = calib["calib_reprojection_px"]
merged["calibration"] = calib
courses_file = os.path.join(out, "courses.json")
if os.path.exists(courses_file):
    courses = json.load(open(courses_file))
    for k in ("courses", "collisions_vision_off", "collisions_vision_on", "reached_vision_off", "reached_vision_on"):
        merged[k] = courses[k]
    merged["obstacle_courses"] = {k: v for k, v in courses.items() if k != "per_course"}
tmp = whole + ".tmp"
with open(tmp, "w") as f:
    json.dump(merged, f, indent=2, sort_keys=True)
    f.write("\n")
os.replace(tmp, whole)
PY
echo "wrote $ROOT/logs/bench/vision.json" >&2
