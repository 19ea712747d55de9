// The base driver without LCM: a SynchroDriveController on a real CanInterface, run in its own
// thread so the drive supervision (SYNC, heartbeats, deadman) keeps its timing whatever the
// caller's loop does. Thread-safe: command() and snapshot() may be called from any thread.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "base_driver/base_driver_options.h"
#include "base_driver/synchro_drive_controller.h"
#include "bus/can_interface.h"

namespace rgnav::can::base {

struct BaseSnapshot
{
  BaseOdometry odometry;
  int64_t sample_wall_utime = 0;  // [us] wall time the newest encoder pair was received (0: none yet)
  uint64_t send_failures = 0;     // frames the CAN interface refused
};

// The interface the options ask for (SocketCan or VirtualCan). Throws CanError.
std::unique_ptr<CanInterface> make_can_interface(const BaseDriverOptions& options);

class BaseDriver
{
 public:
  using Clock = std::chrono::steady_clock;

  BaseDriver(BaseDriverOptions options, std::unique_ptr<CanInterface> bus);
  // Stops the thread (see stop()).
  ~BaseDriver();
  BaseDriver(const BaseDriver&) = delete;
  BaseDriver& operator=(const BaseDriver&) = delete;

  void start();
  // Controlled stop (waits up to stop_timeout for standstill), drives to pre-operational,
  // thread joined. Idempotent.
  void stop();

  // A velocity command, received now, void after `deadline` (capped by the configured one).
  void command(const VelocityCommand& cmd, std::chrono::microseconds deadline);
  // Holds the drives in quick stop while `hold` (SynchroDriveController::quick_stop).
  void quick_stop(bool hold, const std::string& why = "");
  BaseSnapshot snapshot() const;

 private:
  void run();
  void step(Clock::time_point now);

  const BaseDriverOptions options_;
  std::unique_ptr<CanInterface> bus_;
  mutable std::mutex mu_;
  SynchroDriveController controller_;
  BaseSnapshot snapshot_;
  uint64_t last_samples_ = 0;
  std::atomic<bool> running_{false};
  std::atomic<bool> stopping_{false};
  std::thread thread_;
  uint64_t send_failures_ = 0;
};

}  // namespace rgnav::can::base
