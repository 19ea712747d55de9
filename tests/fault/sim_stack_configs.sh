#!/bin/sh
# Writes the configs of tests/fault/sim_stack.pmd into $RGNAV_FAULT_STATE/config: the real
# process configs with private state (map checkpoints, the CAN bus socket) and with the
# inputs that get loss/duplication/delay moved behind the stack's lcm_relays. Every result
# is validated by its process (--check-config) so a stale key fails here, not mid-test.
. "$(dirname "$0")/stack_configs_lib.sh"
"$ov" "$c/sim.yaml" "$out/sim.yaml" channels.command=BASE_CMD_RELAYED sim.world="$c/worlds/office.yaml"
"$ov" "$c/tour_runner.yaml" "$out/tour_runner.yaml" channels.odometry=ODOMETRY_RELAYED
"$ov" "$c/scan_mapper.yaml" "$out/scan_mapper.yaml" channels.laser=LASER_FRONT_RELAYED \
  persistence.state_file="$s/scan_mapper.state"
"$ov" "$c/rg_kernel.yaml" "$out/rg_kernel.yaml" channels.aligned_scan=ALIGNED_SCAN_RELAYED \
  persistence.state_dir="$s/rg_kernel"
# The localizer on a saved map (the two-room map of its tests), not on the kernel's RG_MAP,
# its laser and odometry behind relays of its own.
"$ov" "$c/localizer.yaml" "$out/localizer.yaml" channels.laser=LASER_FRONT_LOCALIZER \
  channels.odometry=ODOMETRY_LOCALIZER channels.rg_map=LOCALIZER_RG_MAP_UNUSED
# The planner on the same saved map, its pose the scan mapper's behind a relay of its own; its
# targets go where nobody listens (the tour runner drives), and it hears no RG_MAP or POSE.
"$ov" "$c/planner.yaml" "$out/planner.yaml" channels.slam_pose=SLAM_POSE_PLANNER \
  channels.rg_map=PLANNER_RG_MAP_UNUSED channels.pose=PLANNER_POSE_UNUSED channels.targets=PLANNER_TARGETS_UNUSED
# The explorer on the kernel's RG_MAP, its pose the scan mapper's behind a relay of its own; its
# goals go where nobody listens (the tour runner drives, the planner keeps its own goal).
"$ov" "$c/explorer.yaml" "$out/explorer.yaml" channels.slam_pose=SLAM_POSE_EXPLORER \
  channels.pose=EXPLORER_POSE_UNUSED channels.nav_goal=EXPLORER_NAV_GOAL_UNUSED \
  channels.global_path=EXPLORER_GLOBAL_PATH_UNUSED
if [ -x "$RGNAV_BUILD/bin/two_room_map" ]; then
  "$RGNAV_BUILD/bin/two_room_map" "$s/localizer_map" || { echo "sim_stack_configs: two_room_map failed" >&2; exit 2; }
fi
# The drive chain: the real base_driver on a virtual CAN bus of its own with two emulated
# CiA 402 drives; it follows the same (relayed) BASE_CMD as the simulated robot and reports
# on DRIVE_ODOMETRY, so the simulator's ODOMETRY stays the only one. Here the tour runner owns
# BASE_CMD (base.command_source), not lld.
"$ov" "$c/base_driver_sim.yaml" "$out/base_driver.yaml" can.virtual_bus_path="$s/vcan.sock" \
  channels.base_cmd=BASE_CMD_RELAYED channels.odometry=DRIVE_ODOMETRY base.command_source=tour_runner
# (tour_runner is checked at launch: its tour file is planned by the stack's tour_plan job.)
check_configs sim_stack_configs rgnav_sim:sim scan_mapper:scan_mapper rg_kernel:rg_kernel base_driver:base_driver \
  localizer:localizer planner:planner explorer:explorer
