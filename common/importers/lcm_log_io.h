// Imported logs as real LCM log files (lcm::LogFile): LASER_FRONT laser_scan_t, LASER_REAR
// laser_scan_t, ODOMETRY odometry_t, REFERENCE_POSE odometry_t (seq = the scan_id the
// reference pose belongs to), in the original order with the original timestamps.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "importers/log_records.h"

namespace lcm { struct LogEvent; }

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

// How a log's events lie in its file, from for_each_lcm_event.
struct LogFraming
{
  int64_t events = 0;               // complete events
  int64_t good_bytes = 0;           // file bytes up to the end of the last complete one
  bool truncated = false;           // bytes after it: a damaged or cut-off last event
  std::vector<ImportIssue> issues;  // damage, by event number ("line")
};

// Calls on_event(event, its number from 1) for every complete event of the LCM log at `path`,
// in file order, and says how the file ended; damage in the middle is an issue (LCM 1.3's
// reader stops there: what follows is then a truncated tail). Throws std::runtime_error naming
// the file when it is missing, empty or no LCM log at all: no complete event, or the first one
// not at its start. Reads the data of every event, decodes none.
LogFraming for_each_lcm_event(const std::string& path,
                              const std::function<void(const lcm::LogEvent&, int64_t)>& on_event);

// Assigns scan ids 1, 2, ... and odometry seq numbers. Throws std::runtime_error if the file
// cannot be written or a record would make an invalid message.
WriteSummary write_lcm_log(const ImportedLog& log, const std::string& path, const LogChannels& channels = {});

// Reads the channels above back; messages that fail validation are reported as issues (their
// event number as "line") and skipped; a truncated log keeps what came before the damage (an
// issue, and `truncated`), as does one with damage in the middle (an issue; reading resumes at
// the next event). Throws std::runtime_error naming the file when it is missing, empty or no
// LCM log at all: no complete event, or the first one not at its start.
ImportedLog read_lcm_log(const std::string& path, const LogChannels& channels = {});

}  // namespace rgnav::importers
