#include "importers/reference_matching.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace rgnav::importers {
namespace {

bool same_scan(const sensors::LaserScan& a, const sensors::LaserScan& b, const ReferenceMatchOptions& o)
{
  if (a.ranges.size() != b.ranges.size()) return false;
  const size_t allowed = static_cast<size_t>(o.max_mismatch_share * static_cast<double>(a.ranges.size()));
  size_t bad = 0, compared = 0;
  for (size_t k = 0; k < a.ranges.size(); ++k) {
    const double x = a.ranges[k], y = b.ranges[k];
    if (x <= 0.0 || y <= 0.0 || x >= o.max_valid_range_m || y >= o.max_valid_range_m) continue;
    ++compared;
    if (std::fabs(x - y) > o.tolerance_m && ++bad > allowed) return false;
  }
  return compared >= o.min_compared_beams;
}

// The corrected pose attached to corrected scan i: its reference record if it has one (same
// utime), else the odometry record at its utime (corrected logs carry corrected odometry).
const PoseRecord* pose_of(const ImportedLog& log, const sensors::LaserScan& s)
{
  for (const auto* list : {&log.reference, &log.odometry}) {
    auto it = std::lower_bound(list->begin(), list->end(), s.utime,
                               [](const PoseRecord& p, int64_t t) { return p.utime < t; });
    // Take the last record with this utime: it is the one written with the scan.
    const PoseRecord* found = nullptr;
    for (; it != list->end() && it->utime == s.utime; ++it) found = &*it;
    if (found) return found;
  }
  return nullptr;
}

}  // namespace

size_t add_reference_from_corrected(const ImportedLog& corrected, ImportedLog* raw,
                                    const ReferenceMatchOptions& o)
{
  std::map<size_t, PoseRecord> by_raw_scan;
  for (const auto& c : corrected.scans) {
    const PoseRecord* pose = pose_of(corrected, c);
    if (!pose) continue;
    size_t hits = 0, hit = 0;
    for (size_t i = 0; i < raw->scans.size() && hits < 2; ++i)
      if (same_scan(c, raw->scans[i], o)) {
        ++hits;
        hit = i;
      }
    if (hits == 1) by_raw_scan[hit] = *pose;
  }
  // Rebuild the event order so each reference sits right after its scan.
  std::vector<LogEvent> events;
  events.reserve(raw->events.size() + by_raw_scan.size());
  for (const auto& e : raw->events) {
    events.push_back(e);
    if (e.kind != LogEvent::Kind::kScan) continue;
    auto it = by_raw_scan.find(e.index);
    if (it == by_raw_scan.end()) continue;
    PoseRecord p = it->second;
    p.utime = raw->scans[e.index].utime;
    events.push_back({LogEvent::Kind::kReference, raw->reference.size()});
    raw->reference.push_back(p);
  }
  raw->events = std::move(events);
  return by_raw_scan.size();
}

}  // namespace rgnav::importers
