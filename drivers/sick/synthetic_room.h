// A ScanSource for tests and manual runs: the laser stands in an axis-aligned rectangular
// room (optionally with a doorway in the front wall that opens onto nothing), so every beam
// has an exact, easily computed range.
#pragma once

#include <vector>

#include "scan_source.h"

namespace rgnav::drivers::sick {

struct SyntheticRoomOptions
{
  double front_m = 3.0;  // distance to the wall ahead (+x)
  double back_m = 2.0;   // behind (-x)
  double left_m = 1.5;   // to the left wall (+y)
  double right_m = 2.5;  // to the right wall (-y)
  // A gap in the front wall between these y values: beams through it see no return.
  double door_y_min_m = 0.0;
  double door_y_max_m = 0.0;
};

class SyntheticRoom final : public ScanSource
{
 public:
  explicit SyntheticRoom(SyntheticRoomOptions options = {});
  std::vector<float> ranges(const ScanRequest& request) override;
  // The exact range at one bearing (+inf through the doorway).
  double range_at(double bearing_rad) const;

 private:
  const SyntheticRoomOptions options_;
};

}  // namespace rgnav::drivers::sick
