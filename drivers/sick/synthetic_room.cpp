#include "synthetic_room.h"

#include <cmath>
#include <limits>

namespace rgnav::drivers::sick {

SyntheticRoom::SyntheticRoom(SyntheticRoomOptions options) : options_(options) {}

double SyntheticRoom::range_at(double bearing_rad) const
{
  const double c = std::cos(bearing_rad);
  const double s = std::sin(bearing_rad);
  constexpr double kEps = 1e-12;
  double best = std::numeric_limits<double>::infinity();
  bool through_door = false;
  if (c > kEps) {
    const double t = options_.front_m / c;
    const double y = t * s;
    if (y >= options_.door_y_min_m && y <= options_.door_y_max_m && options_.door_y_max_m > options_.door_y_min_m)
      through_door = true;
    else
      best = std::min(best, t);
  }
  if (c < -kEps) best = std::min(best, options_.back_m / -c);
  if (s > kEps) best = std::min(best, options_.left_m / s);
  if (s < -kEps) best = std::min(best, options_.right_m / -s);
  // Side walls end at the front wall; past them only the doorway's void remains.
  if (through_door) {
    const double side = s > kEps ? options_.left_m / s : (s < -kEps ? options_.right_m / -s : best);
    if (side * c <= options_.front_m) return side;
    return std::numeric_limits<double>::infinity();
  }
  return best;
}

std::vector<float> SyntheticRoom::ranges(const ScanRequest& request)
{
  std::vector<float> out(static_cast<size_t>(std::max(request.count, 0)));
  for (int i = 0; i < request.count; ++i)
    out[static_cast<size_t>(i)] = static_cast<float>(range_at(request.angle_min_rad + i * request.angle_increment_rad));
  return out;
}

}  // namespace rgnav::drivers::sick
