// Runs drive emulators in real time, each on its own CanInterface (its own client of the
// virtual bus, or its own SocketCAN socket), in the caller's thread: run_once() waits for
// frames on all interfaces, dispatches them, and ticks every emulator with the steady clock.
// Used by the drive_emulator process and by tests; a simulator with its own clock drives
// DriveEmulator directly instead.
#pragma once

#include <chrono>
#include <memory>
#include <vector>

#include "bus/can_interface.h"
#include "emulator/drive_emulator.h"

namespace rgnav::can::emulator {

class EmulatorRunner
{
 public:
  using Clock = std::chrono::steady_clock;

  // The emulator sends through `bus`; both live as long as the runner.
  DriveEmulator& add(std::unique_ptr<CanInterface> bus, const DriveEmulatorOptions& options);
  void power_on(Clock::time_point now);
  // Waits up to max_wait for frames, handles all that are waiting, ticks every emulator.
  void run_once(std::chrono::milliseconds max_wait);

  size_t size() const { return ports_.size(); }
  DriveEmulator& drive(size_t i) { return *ports_[i].drive; }
  CanInterface& bus(size_t i) { return *ports_[i].bus; }
  uint64_t send_failures() const { return send_failures_; }

 private:
  struct Port
  {
    std::unique_ptr<CanInterface> bus;
    std::unique_ptr<DriveEmulator> drive;
  };
  std::vector<Port> ports_;
  uint64_t send_failures_ = 0;
};

}  // namespace rgnav::can::emulator
