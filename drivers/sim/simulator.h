// The simulated B21r in its world, advanced in lock-step: step(dt) moves time forward by dt
// and returns what the robot's sensors produced meanwhile (scans at the LMS rate, odometry at
// the base rate, collisions). Nothing here knows LCM or wall time; the same world, options,
// seed and commands always give the same outputs, bit for bit.
//
// Seams for the two ways the simulator stands in for hardware:
//   - input: a DriveCommandSource says what the drive is told at each instant (direct mode:
//     the newest BASE_CMD until its deadline; protocol mode: the CiA 402 drive emulators'
//     target velocities);
//   - output: StepOutput::scans go to whatever plays the laser (direct mode: LASER_FRONT;
//     protocol mode: the LMS 2xx telegram emulator), StepOutput::odometry to ODOMETRY or to
//     encoder positions (OdometryModel::translation_total / rotation_total).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/lms2xx_model.h"
#include "sim/odometry_model.h"
#include "sim/people.h"
#include "sim/scene.h"
#include "sim/synchro_drive.h"
#include "sim/world.h"

namespace rgnav::sim {

struct RobotOptions
{
  double radius = 0.26;            // [m] B21r footprint
  double height = 1.2;             // [m] anything from ground_clearance up to here is hit by the body
  double ground_clearance = 0.02;  // [m]
};

struct SimulatorOptions
{
  uint64_t seed = 1;
  std::chrono::microseconds physics_step{1000};
  double odometry_hz = 50.0;
  int64_t start_utime = 1'000'000'000'000'000;  // [us] message time of simulation time 0
  bool laser_enabled = true;
  // false (benchmarks of perception only): people are seen by the laser, but neither they nor
  // the robot make way, and the robot's body passes through them (a blind tour follower can
  // then drive a world with walking people).
  bool people_block_robot = true;
  RobotOptions robot;
  SynchroDriveOptions drive;
  OdometryErrorOptions odometry;
  Lms2xxOptions laser;
};

class DriveCommandSource
{
 public:
  virtual ~DriveCommandSource() = default;
  // The velocities the drive is told to reach at message time `utime`; nullopt when there is
  // no valid command (none yet, or stale): the drive then decelerates to a stop.
  virtual std::optional<DriveCommand> command_at(int64_t utime) = 0;
  // True when the commands are drives' velocities after their own ramps (protocol mode: the
  // emulated CiA 402 drives' profile and quick-stop decelerations): the body then slows as the
  // drives do, up to its grip (SynchroDriveOptions::brake_decel). False for raw commands
  // (direct mode): the simulated drive ramps them at its cruise accel both ways.
  virtual bool ramped_by_drives() const { return false; }
};

// The newest command, valid until its deadline; afterwards (or before any command) the drive
// is told to stop, and decelerates within its limits.
class TimedCommandSource final : public DriveCommandSource
{
 public:
  void set(int64_t utime, const DriveCommand& cmd, int64_t deadline_us)
  {
    utime_ = utime;
    cmd_ = cmd;
    deadline_us_ = deadline_us;
    has_ = true;
  }
  bool stale_at(int64_t utime) const { return !has_ || utime >= utime_ + deadline_us_; }
  std::optional<DriveCommand> command_at(int64_t utime) override
  {
    if (stale_at(utime)) return std::nullopt;
    return cmd_;
  }

 private:
  bool has_ = false;
  int64_t utime_ = 0;
  int64_t deadline_us_ = 0;
  DriveCommand cmd_;
};

struct OdometrySample
{
  int64_t utime = 0;
  int64_t seq = 0;
  Pose2 odom_from_base;  // drifting odometry estimate
  double v = 0.0;        // [m/s] measured (drive state)
  double omega = 0.0;    // [rad/s]
  double distance = 0.0; // [m] measured path length
  Pose2 world_from_base; // ground truth
  double true_v = 0.0;   // [m/s] true velocities and path length (no odometry error)
  double true_omega = 0.0;
  double true_distance = 0.0;
  bool commanded = false;  // false when the drive was told to stop (no or stale command)
};

struct CollisionEvent
{
  int64_t utime = 0;
  Pose2 world_from_base;
  std::string with;  // what was hit: "wall[12]", "door d3", "table_1.top", "person p2"
};

struct StepOutput
{
  std::vector<sensors::LaserScan> scans;
  std::vector<OdometrySample> odometry;
  std::vector<CollisionEvent> collisions;
};

class Simulator
{
 public:
  Simulator(World world, const SimulatorOptions& options);

  // Not owned; must outlive its use. nullptr: the drive is told to stop.
  void set_command_source(DriveCommandSource* source) { source_ = source; }

  StepOutput step(std::chrono::microseconds dt);

  int64_t now_utime() const { return options_.start_utime + now_us_; }
  double time_s() const { return static_cast<double>(now_us_) * 1e-6; }
  const Pose2& truth() const { return truth_; }
  const SynchroDrive& drive() const { return drive_; }
  const OdometryModel& odometry() const { return odometry_; }
  const Scene& scene() const { return scene_; }
  const World& world() const { return world_; }
  const SimulatorOptions& options() const { return options_; }
  std::vector<Circle> people() const { return people_.discs(); }
  // What the people chose when they met the robot (benchmarks of encounters).
  const People& people_model() const { return people_; }
  const std::vector<uint8_t>& doors_open() const { return door_open_; }
  int64_t collisions() const { return collision_count_; }
  // Nearest obstacle the robot body could hit (walls, furniture, closed doors, people), from
  // the robot centre; infinity beyond `search` metres.
  double clearance(const Vec2& p, double search, std::string* what = nullptr) const;

 private:
  void physics(int64_t t_end_us, StepOutput* out);
  void update_doors();

  const World world_;
  const SimulatorOptions options_;
  const Scene scene_;
  SynchroDrive drive_;
  OdometryModel odometry_;
  Lms2xxModel laser_;
  People people_;
  DriveCommandSource* source_ = nullptr;
  std::vector<uint8_t> door_open_;
  Pose2 truth_;
  int64_t now_us_ = 0;
  int64_t scans_done_ = 0;
  int64_t odometry_done_ = 0;
  bool commanded_ = false;
  bool in_contact_ = false;
  int64_t collision_count_ = 0;
  double true_distance_ = 0.0;
  double true_v_ = 0.0;
  double true_omega_ = 0.0;
};

}  // namespace rgnav::sim
