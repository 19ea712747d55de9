#!/bin/sh
# Writes the configs of tests/fault/drive_stack.pmd into $RGNAV_FAULT_STATE/config: the real
# process configs (the demo's, in protocol mode) with the CAN bus socket and the laser's pty in
# the run folder, and the inputs that get loss/duplication/delay moved behind the stack's
# lcm_relays. Every result is validated by its process (--check-config) so a stale key fails
# here, not mid-test.
. "$(dirname "$0")/stack_configs_lib.sh"
# The hardware the drivers talk to: the simulator serves the CAN bus and the LMS pty named in
# the driver configs it is given.
"$ov" "$c/laser_driver_sim.yaml" "$out/laser_driver.yaml" laser_driver.port="$s/laser_front"
"$ov" "$c/base_driver_sim.yaml" "$out/base_driver.yaml" can.virtual_bus_path="$s/vcan.sock" \
  channels.base_cmd=BASE_CMD_RELAYED
"$ov" "$c/sim.yaml" "$out/sim.yaml" sim.interface=protocol sim.world="$c/worlds/office.yaml" \
  protocol.laser_driver_config="$out/laser_driver.yaml" protocol.base_driver_config="$out/base_driver.yaml"
# The demo's navigation on the tour runner's targets (odometry only: no scan mapper here).
"$ov" "$c/tour_runner.yaml" "$out/tour_runner.yaml" tour.output=targets channels.slam_pose='""'
"$ov" "$c/lld.yaml" "$out/lld.yaml" channels.trajectory=TRAJECTORY_RELAYED
"$ov" "$c/collision_avoidance.yaml" "$out/collision_avoidance.yaml" channels.laser=LASER_FRONT_CA
"$ov" "$c/gateway_detector.yaml" "$out/gateway_detector.yaml" channels.input=laser channels.laser=LASER_FRONT_GW \
  channels.odometry=ODOMETRY_GW classifier.models="$c/gateway_models/default.yaml"
# Pairs at 2 Hz: the images go to every process of the namespace (udpm), 10 Hz loads two cores.
"$ov" "$c/stereo_capture.yaml" "$out/stereo_capture.yaml" capture.rate_hz=2
# (tour_runner is checked at launch: its tour file is planned by the stack's tour_plan job.)
check_configs drive_stack_configs rgnav_sim:sim laser_driver:laser_driver base_driver:base_driver lld:lld \
  collision_avoidance:collision_avoidance gateway_detector:gateway_detector stereo_capture:stereo_capture
