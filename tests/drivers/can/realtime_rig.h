// Real-time test rig: a virtual CAN bus broker (its own thread), the two emulated drives
// (pumped by the test thread), and a BaseDriver (its own thread) on real CAN clients.
#pragma once

#include <unistd.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "base_driver/base_driver.h"
#include "bus/vcan_broker.h"
#include "bus/virtual_can.h"
#include "config/config.h"
#include "emulator/emulator_runner.h"

namespace rgnav::can::testing {

inline base::BaseDriverOptions shipped_base_driver_options()
{
  return base::load_base_driver_options(
      config::Config::load(std::string(RGNAV_SOURCE_DIR) + "/config/base_driver.yaml"));
}

class RealtimeRig
{
 public:
  using Clock = std::chrono::steady_clock;

  explicit RealtimeRig(const std::string& tag, std::chrono::milliseconds drive_reconnect = std::chrono::milliseconds(300))
      : path_("@rgnav-vcan-" + tag + "-" + std::to_string(::getpid())), broker_(path_)
  {
    broker_.start();
    options_ = shipped_base_driver_options();
    options_.virtual_bus_path = path_;
    options_.stop_timeout = std::chrono::milliseconds(200);  // tests destroy drivers while nobody pumps the drives
    for (uint8_t node : {options_.translation.node_id, options_.rotation.node_id}) {
      VirtualCanOptions v;
      v.path = path_;
      v.client_name = "drive-" + std::to_string(node);
      v.reconnect_interval = drive_reconnect;
      emulator::DriveEmulatorOptions d;
      d.node_id = node;
      runner_.add(std::make_unique<VirtualCan>(v), d);
    }
    runner_.power_on(Clock::now());
  }

  base::BaseDriver& start_driver()
  {
    driver_ = std::make_unique<base::BaseDriver>(options_, base::make_can_interface(options_));
    driver_->start();
    return *driver_;
  }

  // Pumps the emulators (and `also`) until pred() holds; the real time it took, or nullopt.
  std::optional<std::chrono::milliseconds> pump_until(const std::function<bool()>& pred,
                                                      std::chrono::milliseconds limit,
                                                      const std::function<void()>& also = nullptr)
  {
    const auto t0 = Clock::now();
    for (;;) {
      if (pred()) return std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - t0);
      if (Clock::now() - t0 > limit) return std::nullopt;
      runner_.run_once(std::chrono::milliseconds(1));
      if (also) also();
    }
  }
  void pump_for(std::chrono::milliseconds d, const std::function<void()>& also = nullptr)
  {
    pump_until([] { return false; }, d, also);
  }

  emulator::DriveEmulator& translation() { return runner_.drive(0); }
  emulator::DriveEmulator& rotation() { return runner_.drive(1); }
  VcanBroker& broker() { return broker_; }
  base::BaseDriverOptions& options() { return options_; }
  base::BaseDriver& driver() { return *driver_; }

 private:
  std::string path_;
  VcanBroker broker_;
  base::BaseDriverOptions options_;
  emulator::EmulatorRunner runner_;
  std::unique_ptr<base::BaseDriver> driver_;
};

}  // namespace rgnav::can::testing
