// Seconds per microsecond: a utime difference (int64 microseconds) times kUs is in seconds.
#pragma once

namespace rgnav::time {

inline constexpr double kUs = 1e-6;

}  // namespace rgnav::time
