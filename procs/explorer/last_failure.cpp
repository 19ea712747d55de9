#include "explorer/last_failure.h"

#include <stdexcept>

namespace rgnav::explorer {

bool tells_more(const std::optional<LastFailure>& last, const LastFailure& now, double moved_m)
{
  return !last || (now.robot - last->robot).norm() >= moved_m || now.map_version != last->map_version;
}

nlohmann::json last_failure_json(const LastFailure& f) { return {f.robot.x(), f.robot.y(), f.map_version}; }

LastFailure last_failure_from_json(const nlohmann::json& j)
{
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number_integer())
    throw std::invalid_argument("a failure's place is not [x, y, map_version]");
  LastFailure f;
  f.robot = Eigen::Vector2d(j[0].get<double>(), j[1].get<double>());
  f.map_version = j[2].get<int64_t>();
  if (!f.robot.allFinite()) throw std::invalid_argument("a failure's place is not finite");
  return f;
}

}  // namespace rgnav::explorer
