// The Region & Gateway map model (diss. ch. 2, Table 2.1), plain C++: regions with their own
// frames and compact metric descriptions, gateways between them with the transform between
// the adjacent regions' frames, and the bookkeeping of merges (diss. 6.1.1): a region merged
// into another keeps its id (state kMerged, merged_into) so ids held elsewhere stay valid, and
// a gateway that ends up with the same region on both sides is neutralized.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/pose2.h"
#include "rgmap/freespace_bitmap.h"

namespace rgnav::rgmap {

// Same values as the CLASS_* constants of gateway_hypothesis_t / gateway_t.
enum class GatewayClass : int8_t
{
  kUnknown = 0,
  kDoor = 1,
  kNarrowPassage = 2,
  kXCrossing = 3,
  kTCrossing = 4,
  kLTCrossing = 5,
  kRTCrossing = 6,
  kLTurn = 7,
  kRTurn = 8,
  kDeadEnd = 9,
  kHallway = 10,
  kOpening = 11,
};
const char* to_string(GatewayClass c);

// The boundary lines of a gateway from its points: four points are a closed outline (a
// crossing's four sides, diss. fig. 4.1), otherwise consecutive point pairs are lines.
std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> gateway_edges(const std::vector<Eigen::Vector2d>& points);

struct LineSegment
{
  Eigen::Vector2d a{0, 0}, b{0, 0};   // [m] region frame
  double sigma = 0;                    // [m] spread of supporting points
  int support = 0;                     // scan points merged into it
};

struct Object2d
{
  enum class Shape : int8_t { kRectangle = 1, kCircle = 2 };
  int64_t id = 0;
  Shape shape = Shape::kRectangle;
  geometry::Pose2 center;              // region frame
  double length = 0, width = 0;        // [m]
  double confidence = 0;
};

struct Rectangle3d
{
  int64_t id = 0;
  Eigen::Matrix<double, 4, 3> corners = Eigen::Matrix<double, 4, 3>::Zero();  // [m] region frame, z up
  Eigen::Vector3d normal{1, 0, 0};
  double width = 0, height = 0, confidence = 0;
  int8_t kind = 0;                     // rectangle3d_t::KIND_*
};

// `r` in another frame of the plane: corners and normal turned and moved by `to_from`, heights kept.
Rectangle3d moved(Rectangle3d r, const geometry::Pose2& to_from);

struct Region
{
  enum class State : int8_t { kOpen = 1, kFinalised = 2, kMerged = 3 };
  int64_t id = 0;
  std::string name;
  State state = State::kOpen;
  int64_t merged_into = 0;
  int64_t utime = 0;                   // last change (message time)
  geometry::Pose2 map_from_region;
  std::vector<LineSegment> segments;
  std::vector<Object2d> objects;
  std::vector<Rectangle3d> objects3d;
  Eigen::Vector2d bbox_min{0, 0}, bbox_max{0, 0};
  FreespaceBitmap freespace;
  double accuracy = 0, completeness = 0;
  int nscans = 0;
};

struct Gateway
{
  int64_t id = 0;
  GatewayClass cls = GatewayClass::kUnknown;
  int64_t region_a = 0;
  int64_t region_b = 0;                // 0 while not yet traversed
  geometry::Pose2 region_a_from_region_b;
  std::vector<Eigen::Vector2d> gateway_points;   // region_a frame
  std::vector<Eigen::Vector2d> crossing_points;  // region_a frame
  std::vector<double> traversal_directions;      // [rad] region_a frame
  int traversals = 0;
  double mean_traversal_time = 0;      // [s]
  bool neutralized = false;
};

class RgMap
{
 public:
  // Ids are never reused, also across save/load (next ids are part of the map).
  Region& add_region(const geometry::Pose2& map_from_region, int64_t utime);
  Gateway& add_gateway(GatewayClass cls, int64_t region_a, int64_t utime);

  // Loaders (JSON, LCM): insert with the stored id; throws std::invalid_argument on a
  // duplicate or non-positive id.
  Region& insert_region(Region r);
  Gateway& insert_gateway(Gateway g);

  Region* region(int64_t id);
  const Region* region(int64_t id) const;
  Gateway* gateway(int64_t id);
  const Gateway* gateway(int64_t id) const;
  // Follows merged_into to the region that now stands for `id`.
  int64_t resolve(int64_t id) const;

  // Connects gateway g's open side to region b; region_a_from_region_b as measured.
  void connect(int64_t gateway_id, int64_t region_b, const geometry::Pose2& region_a_from_region_b);
  // Merges region `from` into `into` (same place seen twice, diss. 6.1.1): geometry of `from`
  // is moved into `into`'s frame, gateways are re-attached, and gateways with `into` on both
  // sides are neutralized. Returns the number of gateways neutralized.
  int merge(int64_t from, int64_t into, const geometry::Pose2& into_from_from, int64_t utime);

  // Structural checks (no dangling gateway, no region in two places): empty when consistent.
  std::vector<std::string> consistency_problems() const;

  const std::map<int64_t, Region>& regions() const { return regions_; }
  const std::map<int64_t, Gateway>& gateways() const { return gateways_; }
  int64_t current_region = 0;
  int64_t version = 0;
  int64_t last_scan_id = 0;
  int64_t utime = 0;
  int64_t next_region_id() const { return next_region_id_; }
  int64_t next_gateway_id() const { return next_gateway_id_; }
  void set_next_ids(int64_t region, int64_t gateway);

 private:
  std::map<int64_t, Region> regions_;
  std::map<int64_t, Gateway> gateways_;
  int64_t next_region_id_ = 1;
  int64_t next_gateway_id_ = 1;
};

// The live region an operator's name for region `id` goes to (a region merged away: the one it
// was merged into); 0 with *why set when it cannot be named so: no such live region, not a valid
// name (region_name.h), or the name of another live region (names pick one region).
int64_t region_to_name(const RgMap& map, int64_t id, const std::string& name, std::string* why);

}  // namespace rgnav::rgmap
