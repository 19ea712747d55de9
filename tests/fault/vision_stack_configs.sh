#!/bin/sh
# Writes the configs of tests/fault/vision_stack.pmd into $RGNAV_FAULT_STATE/config: the real
# process configs with the vision's and the viewer's inputs moved behind the stack's lcm_relays,
# the head at 2 Hz, the tour runner driving on its own follower. Every result is validated by its
# process (--check-config) so a stale key fails here, not mid-test.
. "$(dirname "$0")/stack_configs_lib.sh"
mkdir -p "$out/stereo"
"$ov" "$c/sim.yaml" "$out/sim.yaml" sim.world="$c/worlds/office.yaml"
"$ov" "$c/tour_runner.yaml" "$out/tour_runner.yaml" tour.output=base_cmd channels.slam_pose='""'
# Pairs at 2 Hz: the images go to every process of the namespace (udpm).
"$ov" "$c/stereo_capture_sim.yaml" "$out/stereo_capture.yaml" capture.rate_hz=2 capture.sim.world="$c/worlds/office.yaml"
cp "$c/stereo/sim_b21r_head.yml" "$out/stereo/"   # stereo_capture and the vision read stereo/<id>.yml beside their config
"$ov" "$c/vision.yaml" "$out/vision.yaml" channels.stereo=STEREO_IMAGES_VISION channels.odometry=ODOMETRY_VISION \
  channels.laser=LASER_FRONT_VISION
"$ov" "$c/viewer.yaml" "$out/viewer.yaml" channels.laser=LASER_FRONT_VIEWER channels.objects3d=OBJECTS_3D_VIEWER
# (tour_runner is checked at launch: its tour file is planned by the stack's tour_plan job.)
check_configs vision_stack_configs rgnav_sim:sim stereo_capture:stereo_capture vision:vision viewer:viewer
