// CARMEN log text (plain or gzip): FLASER / RLASER (old front/rear laser), ODOM, ROBOTLASER1.
// Other message types (PARAM, NEFF, SYNC, ...) and comments are skipped silently; a known
// message with the wrong number of fields or a non-number is reported with its line number
// and skipped; a truncated gzip stream keeps every complete line before the damage.
#pragma once

#include <string>

#include "importers/log_records.h"

namespace rgnav::importers {

struct CarmenOptions
{
  // FLASER/RLASER carry no range limit; readings at or above this are "no return".
  float old_laser_range_max = 80.f;
  // Take the FLASER pose (x y theta) as a published corrected pose and also emit it as a
  // reference record (for logs whose poses come from a SLAM solution, laser/corrected/).
  bool flaser_pose_is_reference = false;
  // FLASER/RLASER beams span the 180 deg field of view inclusive of both ends (increment
  // fov / (n - 1)) whatever n is, as MRPT's CObservation2DRangeScan spreads them. CARMEN's own
  // convention for 180 beams is [-90, 89] deg at 1 deg, and logs that came from CARMEN keep it
  // even when decoded from an MRPT rawlog (deploy/bench/slam.sh's raw log).
  bool fov_inclusive = false;
};

// Parses one CARMEN line into `log` (nothing for lines without data). Returns false with
// `why` for a malformed known message.
bool parse_carmen_line(const std::string& line, const CarmenOptions& options, ImportedLog* log,
                       std::string* why);

// Throws std::runtime_error only if the file cannot be opened.
ImportedLog read_carmen(const std::string& path, const CarmenOptions& options = {});

}  // namespace rgnav::importers
