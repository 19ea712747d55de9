// Re-pairs a log's odometry with its scans when the two are out of step by whole scans.
//
// Some logs pair each scan with the wrong odometry reading: a raw log decoded from an MRPT
// rawlog can give every scan the pose *after* the movement that follows it (one scan ahead;
// its odometry increments correlate best with the scan-matched ones one scan later, see
// deploy/bench/slam.sh). Delaying the odometry by that many scans gives each scan the pose it
// was taken at. Timestamps are kept; only the poses move.
#pragma once

#include "importers/log_records.h"

namespace rgnav::importers {

// Every odometry record gets the pose the odometry had `scans` scans earlier (the last pose
// before that scan); records before the first such scan keep the first pose. Returns the number
// of records changed. scans <= 0 leaves the log as it is.
size_t delay_odometry_by_scans(ImportedLog* log, int scans);

}  // namespace rgnav::importers
