// The low-level drive's node adapter. Two threads:
//   - the Node's thread (run()): subscriptions, heartbeats. TRAJECTORY messages are converted
//     and their velocity profiles computed here (this allocates), ODOMETRY is copied into an
//     inbox;
//   - the control thread: a 20 Hz loop on absolute deadlines that takes the newest inputs
//     from the inbox (a short lock, no allocation), runs the Follower, and publishes BASE_CMD
//     and LLD_STATUS by encoding into buffers reserved up front. It never waits on the bus
//     and never frees a plan (replaced plans go back to the Node's thread).
// Tests drive control_step() directly over a FakeBus, without the thread.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "lld/follower.h"
#include "lld/lld_options.h"
#include "lld/periodic_loop.h"
#include "lld/stall_credit.h"
#include "rgnav/lld_status_t.hpp"
#include "rgnav/odometry_t.hpp"
#include "rgnav/trajectory_t.hpp"
#include "rgnav/velocity_cmd_t.hpp"
#include "runtime/node.h"
#include "time/robot_clock.h"

namespace rgnav::lld {

class LldNode
{
 public:
  // start_thread = false: the caller runs control_step() itself (tests).
  LldNode(runtime::Node& node, const LldOptions& options, bool start_thread = true);
  ~LldNode();
  LldNode(const LldNode&) = delete;
  LldNode& operator=(const LldNode&) = delete;

  // Message time now, as the control loop reads it: the newest input's stamp plus the wall time
  // since it arrived.
  time::Time message_now() const;

  // One control period at message time `now`.
  void control_step(time::Time now, double dt, double jitter_ms);

  // Ends the control loop and joins its thread (the destructor does it too): the stats read
  // afterwards are final.
  void stop_loop();
  LoopStats loop_stats() const { return loop_.stats(); }
  const Follower& follower() const { return follower_; }

 private:
  using Steady = std::chrono::steady_clock;
  struct Inbox
  {
    OdometryInput odometry;
    bool has_odometry = false;
    std::unique_ptr<Plan> pending;    // newest plan not yet taken by the loop
    std::unique_ptr<Plan> retired;    // replaced plans, freed by the Node's thread
    int64_t refresh_id = 0;
    bool has_refresh = false;
    int64_t anchor_utime = 0;         // newest input's message time ...
    Steady::time_point anchor_steady{};  // ... and when it arrived
  };
  // [us] An input stamped more than this ahead of the newest one is held until another confirms
  // it (RobotClock): one corrupted stamp would otherwise make the odometry look stale and stop
  // the robot for as long as the stamp is ahead. Inputs come at 50 Hz; a real gap this long
  // costs one input.
  static constexpr int64_t kMaxStampJumpUs = 1'000'000;
  static constexpr int64_t kStampConfirmUs = 250'000;

  // Under inbox_mutex_: takes the input's stamp into the anchor, or drops the input (counted).
  bool take_stamp(int64_t utime, const std::string& channel);

  void on_trajectory(const trajectory_t& msg);
  void on_odometry(const odometry_t& msg);
  void control_thread();
  void publish_outputs(time::Time now, double jitter_ms);
  void update_heartbeat();

  runtime::Node& node_;
  const LldOptions options_;
  Follower follower_;
  StallCredit stall_credit_;   // control thread only
  PeriodicLoop loop_;

  mutable std::mutex inbox_mutex_;
  time::RobotClock clock_{kMaxStampJumpUs, kStampConfirmUs};  // under inbox_mutex_
  Inbox inbox_;
  std::atomic<double> v_command_{0.0};   // for profiles of new plans
  std::atomic<int> state_{0};
  std::atomic<int> stop_reason_{0};
  bool stale_stop_logged_ = false;   // a stop for stale input is logged once, when it begins
  std::atomic<int64_t> loop_gaps_{0};  // control cycles that came after a gap (halt()); logged by the Node's thread
  std::atomic<double> last_gap_ms_{0.0};  // the newest gap's lateness
  int64_t loop_gaps_logged_ = 0;       // Node's thread only
  int64_t last_trajectory_id_ = 0;       // Node's thread only

  // Control thread only: reused messages and buffers.
  velocity_cmd_t cmd_msg_;
  lld_status_t status_msg_;
  std::vector<uint8_t> cmd_buf_;
  std::vector<uint8_t> status_buf_;
  int64_t seq_ = 0;
  int idle_left_ = 0;

  std::thread thread_;
};

}  // namespace rgnav::lld
