#include "emulator/emulator_runner.h"

#include <poll.h>

#include <thread>

namespace rgnav::can::emulator {

DriveEmulator& EmulatorRunner::add(std::unique_ptr<CanInterface> bus, const DriveEmulatorOptions& options)
{
  CanInterface* raw = bus.get();
  auto drive = std::make_unique<DriveEmulator>(options, [this, raw](const can_frame& f) {
    // A full transmit queue loses the frame, as a real controller would; the master notices.
    if (!raw->send(f, std::chrono::milliseconds(2))) ++send_failures_;
  });
  ports_.push_back({std::move(bus), std::move(drive)});
  return *ports_.back().drive;
}

void EmulatorRunner::power_on(Clock::time_point now)
{
  for (auto& p : ports_) p.drive->power_on(now);
}

void EmulatorRunner::run_once(std::chrono::milliseconds max_wait)
{
  std::vector<pollfd> fds;
  for (auto& p : ports_)
    if (p.bus->fd() >= 0) fds.push_back({p.bus->fd(), POLLIN, 0});
  if (fds.empty())
    std::this_thread::sleep_for(max_wait);
  else
    ::poll(fds.data(), fds.size(), static_cast<int>(max_wait.count()));
  for (auto& p : ports_) {
    // receive() also notices lost connections and reconnects (fd may be -1 meanwhile).
    while (auto f = p.bus->receive(std::chrono::milliseconds(0))) p.drive->handle(*f, Clock::now());
  }
  const auto now = Clock::now();
  for (auto& p : ports_) p.drive->tick(now);
}

}  // namespace rgnav::can::emulator
