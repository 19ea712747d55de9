// The CANopen master of one bus: NMT master and heartbeat producer, SYNC producer, heartbeat
// consumer of every drive, EMCY consumer, SDO client, and a DriveMaster per CiA 402 drive.
// It routes received frames, and per SYNC period sends SYNC followed by each drive's RPDO.
// Bus-off and its recovery arrive as error frames. Pure state machine (see DriveMaster).
#pragma once

#include <linux/can.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "master/drive_master.h"
#include "master/heartbeat_monitor.h"
#include "master/sdo_client.h"

namespace rgnav::can::master {

struct CanopenMasterOptions
{
  uint8_t node_id = 1;                              // the master's own heartbeat id
  std::chrono::milliseconds heartbeat_period{20};   // master heartbeat producer
  std::chrono::milliseconds sync_period{10};        // SYNC (and RPDO) cycle
  SdoClientOptions sdo;
};

class CanopenMaster
{
 public:
  using Clock = std::chrono::steady_clock;
  using Sink = std::function<void(const can_frame&)>;

  CanopenMaster(CanopenMasterOptions options, Sink send);

  // The DriveMaster lives as long as this master.
  DriveMaster& add_drive(const DriveMasterOptions& options);

  void handle(const can_frame& f, Clock::time_point now);
  void tick(Clock::time_point now);

  bool bus_off() const { return bus_off_; }
  // Error frames seen (bus-off, error-passive, ...), newest description.
  const std::string& last_bus_error() const { return last_bus_error_; }
  // SYNC cycles sent; a caller can act once per cycle.
  uint64_t sync_count() const { return sync_count_; }
  const std::vector<std::unique_ptr<DriveMaster>>& drives() const { return drives_; }

 private:
  DriveMaster* drive(uint8_t node);

  CanopenMasterOptions options_;
  Sink send_;
  SdoClient sdo_;
  HeartbeatMonitor monitor_;
  std::vector<std::unique_ptr<DriveMaster>> drives_;
  bool started_ = false;
  bool bus_off_ = false;
  std::string last_bus_error_;
  Clock::time_point next_heartbeat_{};
  Clock::time_point next_sync_{};
  uint64_t sync_count_ = 0;
};

}  // namespace rgnav::can::master
