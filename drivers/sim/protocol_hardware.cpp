#include "sim/protocol_hardware.h"

#include <spdlog/spdlog.h>

#include <filesystem>

#include "can/bus/virtual_can.h"

namespace rgnav::sim {

namespace {

// Salt of the protocol laser's noise stream (the simulator's own streams use 1 and 2).
constexpr uint64_t kProtocolLaserSalt = 3;

std::unique_ptr<can::CanInterface> connect(const ProtocolOptions& o, uint8_t node)
{
  can::VirtualCanOptions v;
  v.path = o.can_bus_path;
  v.client_name = "drive-" + std::to_string(node);
  v.connect_timeout = std::chrono::milliseconds(o.files.internal_broker ? 2000 : 5000);
  // An external broker may restart; the drives come back with it, as after a bus-off.
  v.reconnect_interval = std::chrono::milliseconds(200);
  return std::make_unique<can::VirtualCan>(v);
}

void make_parent_dir(const std::string& path)
{
  const auto parent = std::filesystem::path(path).parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) throw std::runtime_error("cannot create " + parent.string() + " for " + path + ": " + ec.message());
}

}  // namespace

ProtocolHardware::ProtocolHardware(const ProtocolOptions& options, Simulator& sim) : options_(options), sim_(sim)
{
  if (options_.files.internal_broker) {
    if (options_.can_bus_path[0] != '@') make_parent_dir(options_.can_bus_path);
    broker_ = std::make_unique<can::VcanBroker>(options_.can_bus_path);
    broker_->start(options_.bus_realtime_priority);
  }
  translation_bus_ = connect(options_, options_.axes.translation.node_id);
  rotation_bus_ = connect(options_, options_.axes.rotation.node_id);
  // A full transmit queue loses the frame, as on a real controller; the master notices.
  auto sink = [this](can::CanInterface* bus) {
    return [this, bus](const can_frame& f) {
      if (!bus->send(f, std::chrono::milliseconds(2))) ++send_failures_;
    };
  };
  drives_ = std::make_unique<ProtocolDrives>(options_.axes, sink(translation_bus_.get()), sink(rotation_bus_.get()));
  drives_->power_on(sim.now_utime());
  sim.set_command_source(drives_.get());

  scans_ = std::make_shared<SimScanSource>(sim.scene(), sim.options().laser,
                                           Rng::derive(sim.options().seed, kProtocolLaserSalt));
  scans_->record(sim);
  make_parent_dir(options_.laser_port);
  drivers::sick::EmulatorOptions laser;
  laser.symlink_path = options_.laser_port;
  laser_ = std::make_unique<drivers::sick::Lms2xxEmulator>(laser, scans_);
  spdlog::info("protocol mode: LMS 291 on {}; drives {} (translation) and {} (rotation) on {} ({} bus)",
               laser_->port_path(), options_.axes.translation.node_id, options_.axes.rotation.node_id,
               options_.can_bus_path, options_.files.internal_broker ? "internal" : "external");
}

ProtocolHardware::~ProtocolHardware()
{
  // The laser thread reads the simulator: stop it first. Then the drives leave the bus.
  laser_.reset();
  sim_.set_command_source(nullptr);
  if (send_failures_ > 0) spdlog::warn("protocol mode: {} CAN frames could not be sent", send_failures_);
}

void ProtocolHardware::pump(int64_t utime)
{
  // receive() also notices a lost broker and reconnects.
  while (auto f = translation_bus_->receive(std::chrono::milliseconds(0))) drives_->handle_translation(*f, utime);
  while (auto f = rotation_bus_->receive(std::chrono::milliseconds(0))) drives_->handle_rotation(*f, utime);
  drives_->tick(utime);
}

StepOutput ProtocolHardware::advance(std::chrono::microseconds dt)
{
  Simulator& sim = sim_;
  StepOutput all;
  const int64_t step = sim.options().physics_step.count();
  for (int64_t left = dt.count(); left > 0;) {
    const int64_t sub = std::min(step, left);
    pump(sim.now_utime());
    StepOutput out = sim.step(std::chrono::microseconds(sub));
    drives_->report(sim);
    scans_->record(sim);
    for (auto& s : out.odometry) all.odometry.push_back(s);
    for (auto& c : out.collisions) all.collisions.push_back(std::move(c));
    left -= sub;
  }
  return all;
}

}  // namespace rgnav::sim
