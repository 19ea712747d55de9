#include "importers/odometry_alignment.h"

#include <vector>

namespace rgnav::importers {

size_t delay_odometry_by_scans(ImportedLog* log, int scans)
{
  if (scans <= 0 || log->odometry.empty()) return 0;
  // The pose the odometry had when each front scan arrived (index into log->odometry, -1: none yet),
  // and for each odometry record, how many scans came before it.
  std::vector<long> pose_at_scan;
  std::vector<long> scans_before(log->odometry.size(), 0);
  long last = -1;
  for (const auto& e : log->events) {
    if (e.kind == LogEvent::Kind::kOdometry) {
      last = static_cast<long>(e.index);
      scans_before[e.index] = static_cast<long>(pose_at_scan.size());
    } else if (e.kind == LogEvent::Kind::kScan) {
      pose_at_scan.push_back(last);
    }
  }
  const std::vector<PoseRecord> original = log->odometry;
  size_t changed = 0;
  for (size_t i = 0; i < original.size(); ++i) {
    // This record sits between scan k-1 and scan k (k = scans_before[i]): its pose is the one
    // the odometry reported `scans` scans earlier, i.e. at scan k - scans.
    const long k = scans_before[i] - scans;
    long source = 0;
    if (k >= 0 && pose_at_scan[static_cast<size_t>(k)] >= 0) source = pose_at_scan[static_cast<size_t>(k)];
    PoseRecord& p = log->odometry[i];
    const PoseRecord& s = original[static_cast<size_t>(source)];
    if (p.x != s.x || p.y != s.y || p.theta != s.theta) ++changed;
    p.x = s.x;
    p.y = s.y;
    p.theta = s.theta;
  }
  return changed;
}

}  // namespace rgnav::importers
