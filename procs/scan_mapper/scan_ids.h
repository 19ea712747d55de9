// Ids of the scans the mapper publishes (ALIGNED_SCAN, SLAM_POSE). Consumers (RG kernel,
// gateway detector) key scans by id, so an id must never repeat and must grow, also across a
// restart of the scan mapper (the state carries this) or of the laser driver (whose ids start
// at 1 again). While the laser's ids grow, the published id is the laser's id (so images
// tagged with a laser scan id still find it); once they go back, an offset keeps the
// published ids above every id issued before.
#pragma once

#include <cstdint>

namespace rgnav::scan_mapper {

struct ScanIdState
{
  int64_t last_laser_id = 0;  // newest laser scan id seen
  int64_t offset = 0;         // published id = laser id + offset
  int64_t last_issued = 0;    // newest id given to an accepted scan
};

class ScanIdIssuer
{
 public:
  ScanIdIssuer() = default;
  explicit ScanIdIssuer(ScanIdState s) : s_(s) {}

  // The id a scan with this laser id would get; true in *restarted if the laser's ids went
  // back (the offset moved). laser_id must be > 0.
  int64_t id_for(int64_t laser_id, bool* restarted = nullptr);
  // The scan with this id was accepted and published.
  void issued(int64_t id)
  {
    if (id > s_.last_issued) s_.last_issued = id;
  }
  const ScanIdState& state() const { return s_; }

 private:
  ScanIdState s_;
};

}  // namespace rgnav::scan_mapper
