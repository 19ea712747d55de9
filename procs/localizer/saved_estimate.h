// The last estimate on disk, so that a restarted localizer resumes tracking near it (and falls
// back to global localization if it does not hold). Written atomically (persist/atomic_file.h);
// a missing, corrupt or foreign file is no estimate.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "geometry/pose2.h"

namespace rgnav::localizer {

struct SavedEstimate
{
  int64_t utime = 0;
  int64_t region = 0;
  geometry::Pose2 region_from_base;
  geometry::Pose2 map_from_base;
  int64_t map_version = 0;
};

void save_estimate(const std::string& path, const SavedEstimate& e);
// nullopt when there is none; `problem` (if given) says why a file there was not used.
std::optional<SavedEstimate> load_estimate(const std::string& path, std::string* problem = nullptr);

}  // namespace rgnav::localizer
