// Imported logs as real LCM log files (lcm::LogFile): LASER_FRONT laser_scan_t, LASER_REAR
// laser_scan_t, ODOMETRY odometry_t, REFERENCE_POSE odometry_t (seq = the scan_id the
// reference pose belongs to), in the original order with the original timestamps.
#pragma once

#include <string>

#include "importers/log_records.h"

namespace rgnav::importers {

struct LogChannels
{
  std::string laser_front = "LASER_FRONT";
  std::string laser_rear = "LASER_REAR";
  std::string odometry = "ODOMETRY";
  std::string reference = "REFERENCE_POSE";
};

struct WriteSummary
{
  size_t scans = 0, rear_scans = 0, odometry = 0, reference = 0;
};

// Assigns scan ids 1, 2, ... and odometry seq numbers. Throws std::runtime_error if the file
// cannot be written or a record would make an invalid message.
WriteSummary write_lcm_log(const ImportedLog& log, const std::string& path, const LogChannels& channels = {});

// Reads the channels above back; messages that fail validation are reported as issues (their
// event number as "line") and skipped; a truncated log keeps what came before the damage.
ImportedLog read_lcm_log(const std::string& path, const LogChannels& channels = {});

}  // namespace rgnav::importers
