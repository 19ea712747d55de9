#include "master/canopen_master.h"

#include <spdlog/spdlog.h>

#include "bus/can_frames.h"
#include "canopen/emcy.h"

namespace rgnav::can::master {

CanopenMaster::CanopenMaster(CanopenMasterOptions options, Sink send)
    : options_(options), send_(std::move(send)), sdo_(options.sdo, [this](const can_frame& f) {
        if (!bus_off_) send_(f);
      })
{
}

DriveMaster& CanopenMaster::add_drive(const DriveMasterOptions& options)
{
  monitor_.watch(options.node_id, options.heartbeat_timeout);
  drives_.push_back(std::make_unique<DriveMaster>(options, &sdo_, [this](const can_frame& f) {
    if (!bus_off_) send_(f);
  }));
  return *drives_.back();
}

DriveMaster* CanopenMaster::drive(uint8_t node)
{
  for (auto& d : drives_)
    if (d->node_id() == node) return d.get();
  return nullptr;
}

void CanopenMaster::handle(const can_frame& f, Clock::time_point now)
{
  if (is_error_frame(f)) {
    const ErrorFrameInfo info = classify_error(f);
    last_bus_error_ = info.text;
    if (info.bus_off && !bus_off_) {
      spdlog::error("CAN bus-off: stopping all traffic");
      bus_off_ = true;
      for (auto& d : drives_) d->on_bus_off(now);
    }
    if (info.restarted && bus_off_) {
      spdlog::warn("CAN controller restarted after bus-off: reconfiguring the drives");
      bus_off_ = false;
      monitor_.reset();  // silence during bus-off is no heartbeat loss
      next_heartbeat_ = now;
    }
    return;
  }
  if (bus_off_) return;
  if (auto hb = monitor_.handle(f, now)) {
    if (DriveMaster* d = drive(hb->first)) d->on_heartbeat(hb->second, now);
    return;
  }
  if (auto e = canopen::emcy::parse(f)) {
    if (DriveMaster* d = drive(e->node_id)) d->on_emcy(*e, now);
    return;
  }
  if (sdo_.handle(f, now)) return;
  for (auto& d : drives_)
    if (d->on_pdo(f, now)) return;
}

void CanopenMaster::tick(Clock::time_point now)
{
  if (!started_) {
    started_ = true;
    next_heartbeat_ = now;
    next_sync_ = now;
  }
  if (bus_off_) return;  // a bus-off controller sends nothing; the drives stop on their own
  for (uint8_t node : monitor_.tick(now))
    if (DriveMaster* d = drive(node)) d->on_heartbeat_lost(now);
  if (now >= next_heartbeat_) {
    send_(canopen::make_heartbeat(options_.node_id, canopen::NmtState::kOperational));
    next_heartbeat_ += options_.heartbeat_period;
    if (next_heartbeat_ <= now) next_heartbeat_ = now + options_.heartbeat_period;
  }
  sdo_.tick(now);
  for (auto& d : drives_) d->tick(now);
  if (now >= next_sync_) {
    send_(canopen::make_sync());
    ++sync_count_;
    for (auto& d : drives_)
      if (auto f = d->rpdo(now)) send_(*f);
    next_sync_ += options_.sync_period;
    if (next_sync_ <= now) next_sync_ = now + options_.sync_period;
  }
}

}  // namespace rgnav::can::master
