// Shared pieces of the driver ↔ emulator tests: a unique port name, driver options for a
// fast test, and a loop that services the driver until a condition holds.
#pragma once

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "lms2xx_driver.h"

namespace rgnav::drivers::sick::testing {

inline std::string unique_port_name(const std::string& tag)
{
  static std::atomic<int> n{0};
  return "/tmp/rgnav_sick_" + tag + "_" + std::to_string(getpid()) + "_" + std::to_string(n++);
}

inline DriverOptions fast_options(const std::string& port)
{
  DriverOptions o;
  o.port = port;
  o.initial_baud = 9600;
  o.desired_baud = 500000;
  o.variant = {180, 100};
  o.units = Units::kMillimetres;
  o.reply_timeout = std::chrono::milliseconds(500);
  o.detect_timeout = std::chrono::milliseconds(200);
  o.silence_timeout = std::chrono::milliseconds(300);
  o.reconnect_interval = std::chrono::milliseconds(100);
  return o;
}

// Services the driver, appending scans to *scans, until pred() or the timeout (generous:
// these bound a hang, they do not measure speed). Returns pred().
inline bool run_until(Lms2xxDriver& driver, std::vector<Lms2xxScan>* scans, const std::function<bool()>& pred,
                      std::chrono::milliseconds timeout = std::chrono::seconds(10))
{
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!pred()) {
    if (std::chrono::steady_clock::now() > end) return false;
    for (auto& s : driver.poll(std::chrono::milliseconds(10))) scans->push_back(std::move(s));
  }
  return true;
}

}  // namespace rgnav::drivers::sick::testing
