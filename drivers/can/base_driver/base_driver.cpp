#include "base_driver/base_driver.h"

#include <poll.h>
#include <spdlog/spdlog.h>

#include "bus/socket_can.h"
#include "bus/virtual_can.h"
#include "canopen/protocol.h"
#include "runtime/realtime.h"
#include "time/message_time.h"

namespace rgnav::can::base {

std::unique_ptr<CanInterface> make_can_interface(const BaseDriverOptions& options)
{
  std::unique_ptr<CanInterface> bus;
  if (options.interface == "socketcan") {
    bus = std::make_unique<SocketCan>(options.socketcan_device);
  } else {
    VirtualCanOptions v;
    v.path = options.virtual_bus_path;
    v.client_name = options.virtual_client_name;
    v.connect_timeout = std::chrono::milliseconds(5000);
    v.reconnect_interval = std::chrono::milliseconds(200);
    bus = std::make_unique<VirtualCan>(v);
  }
  // The master needs bus-off and restart notices; other error classes are logged.
  bus->set_error_mask(CAN_ERR_MASK);
  return bus;
}

BaseDriver::BaseDriver(BaseDriverOptions options, std::unique_ptr<CanInterface> bus)
    : options_(std::move(options)), bus_(std::move(bus)), controller_(options_, [this](const can_frame& f) {
        // Called with mu_ held, from the driver thread only.
        if (!bus_->send(f, std::chrono::milliseconds(2))) ++send_failures_;
      })
{
}

BaseDriver::~BaseDriver() { stop(); }

void BaseDriver::start()
{
  if (running_.exchange(true)) return;
  thread_ = std::thread([this] { run(); });
}

void BaseDriver::stop()
{
  if (!running_) return;
  stopping_ = true;
  if (thread_.joinable()) thread_.join();
  running_ = false;
}

void BaseDriver::command(const VelocityCommand& cmd, std::chrono::microseconds deadline)
{
  std::lock_guard<std::mutex> lock(mu_);
  controller_.command(cmd, Clock::now(), deadline);
}

void BaseDriver::quick_stop(bool hold, const std::string& why)
{
  std::lock_guard<std::mutex> lock(mu_);
  controller_.quick_stop(hold, why);
}

BaseSnapshot BaseDriver::snapshot() const
{
  std::lock_guard<std::mutex> lock(mu_);
  return snapshot_;
}

void BaseDriver::step(Clock::time_point now)
{
  while (auto f = bus_->receive(std::chrono::milliseconds(0))) {
    std::lock_guard<std::mutex> lock(mu_);
    controller_.handle(*f, Clock::now());
  }
  std::lock_guard<std::mutex> lock(mu_);
  controller_.tick(now);
  snapshot_.odometry = controller_.odometry();
  if (snapshot_.odometry.samples != last_samples_) {
    last_samples_ = snapshot_.odometry.samples;
    snapshot_.sample_wall_utime = time::wall_utime();
  }
  snapshot_.send_failures = send_failures_;
}

void BaseDriver::run()
{
  if (options_.realtime_priority > 0 || options_.lock_memory)
    runtime::request_realtime_logged("base driver CAN thread", options_.realtime_priority, options_.lock_memory,
                                     "heartbeat supervision may trip under load");
  std::optional<Clock::time_point> stop_deadline;
  for (;;) {
    // Wake on frames, and at least every 2 ms for SYNC, heartbeats and the deadman.
    const int fd = bus_->fd();
    if (fd >= 0) {
      pollfd p{fd, POLLIN, 0};
      ::poll(&p, 1, 2);
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    const auto now = Clock::now();
    if (stopping_ && !stop_deadline) {
      std::lock_guard<std::mutex> lock(mu_);
      controller_.release();
      stop_deadline = now + options_.stop_timeout;
    }
    step(now);
    if (stop_deadline) {
      std::lock_guard<std::mutex> lock(mu_);
      if (controller_.at_standstill() || now >= *stop_deadline) break;
    }
  }
  // Release the drives: pre-operational ends their PDOs, they stay disabled and stopped.
  for (const auto* d : {&controller_.translation(), &controller_.rotation()})
    bus_->send(canopen::make_nmt(canopen::NmtCommand::kEnterPreOperational, d->node_id()), std::chrono::milliseconds(5));
  spdlog::info("base driver stopped, drives released");
}

}  // namespace rgnav::can::base
