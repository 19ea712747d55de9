// Plain records of a recorded laser log, independent of its file format and of LCM: what the
// importers parse (CARMEN, Mines) and what the LCM log writer/reader exchange. Scans are
// sensors::LaserScan; their scan_id is 0 until written to / read from an LCM log.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sensors/laser_scan.h"

namespace rgnav::importers {

// A planar pose sample (odometry or a reference pose) at a time.
struct PoseRecord
{
  int64_t utime = 0;  // [us]
  int64_t seq = 0;    // LCM odometry_t.seq; for reference poses the scan_id they belong to
  double x = 0.0;     // [m]
  double y = 0.0;     // [m]
  double theta = 0.0; // [rad]
};

// A line the parser could not use, with its 1-based line number.
struct ImportIssue
{
  int64_t line = 0;
  std::string what;
};

// One record of the log, in file order.
struct LogEvent
{
  enum class Kind { kScan, kRearScan, kOdometry, kReference };
  Kind kind;
  size_t index;  // into ImportedLog::scans / rear_scans / odometry / reference
};

struct ImportedLog
{
  std::string format;  // "carmen", "mines", "lcm"
  std::vector<sensors::LaserScan> scans;       // front laser
  std::vector<sensors::LaserScan> rear_scans;  // rear laser (CARMEN RLASER), if any
  std::vector<PoseRecord> odometry;
  std::vector<PoseRecord> reference;  // published corrected poses, when the log has them
  std::vector<LogEvent> events;       // file order of all records
  std::vector<ImportIssue> issues;    // malformed lines, skipped
  bool truncated = false;             // the input ended early (e.g. a cut gzip stream)
  int64_t lines = 0;                  // lines read

  void add_scan(sensors::LaserScan s)
  {
    events.push_back({LogEvent::Kind::kScan, scans.size()});
    scans.push_back(std::move(s));
  }
  void add_rear_scan(sensors::LaserScan s)
  {
    events.push_back({LogEvent::Kind::kRearScan, rear_scans.size()});
    rear_scans.push_back(std::move(s));
  }
  void add_odometry(PoseRecord p)
  {
    events.push_back({LogEvent::Kind::kOdometry, odometry.size()});
    odometry.push_back(p);
  }
  void add_reference(PoseRecord p)
  {
    events.push_back({LogEvent::Kind::kReference, reference.size()});
    reference.push_back(p);
  }
};

}  // namespace rgnav::importers
