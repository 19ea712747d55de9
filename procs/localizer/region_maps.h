// The localizer's view of the RG map (diss. 5.3): per live region its distance field and
// freespace bitmap, and its links through gateways to the neighbouring regions, with the
// transform between the two frames as the gateway measured it. The localizer keeps the maps
// of all regions, so that particles can be handed across any gateway and global localization
// can search every region.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "geometry/pose2.h"
#include "localizer/likelihood_field.h"
#include "localizer/localizer_options.h"
#include "rgmap/rg_map.h"

namespace rgnav::localizer {

using Line = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

struct RegionLink
{
  int64_t gateway = 0;
  int64_t to = 0;                      // the neighbouring region
  geometry::Pose2 here_from_there;     // this region's frame <- the neighbour's frame
  std::vector<Line> lines;             // the gateway's boundary lines, this region's frame
};

struct RegionModel
{
  int64_t id = 0;
  std::string name;
  geometry::Pose2 map_from_region;
  int64_t utime = 0;                   // the region's last change
  std::string stack_key;               // its and its neighbours' changes: the field is rebuilt when it differs
  LikelihoodField field;               // own lines and the neighbours' (stacked), this region's frame
  rgmap::FreespaceBitmap freespace;
  std::vector<RegionLink> links;
  std::vector<Eigen::Vector2d> free_positions;  // cell centres for particle seeding, region frame
  Eigen::Vector2d bbox_min{0, 0}, bbox_max{0, 0};   // bounding rectangle of its in-region measurements

  bool is_free(const Eigen::Vector2d& p) const { return freespace.is_free(p); }
  // Inside the bounding rectangle grown by `margin`.
  bool in_bbox(const Eigen::Vector2d& p, double margin) const
  {
    return p.x() > bbox_min.x() - margin && p.y() > bbox_min.y() - margin && p.x() < bbox_max.x() + margin &&
           p.y() < bbox_max.y() + margin;
  }
  // Distance from p to the nearest gateway line of this region (infinity without gateways).
  double gateway_distance(const Eigen::Vector2d& p, const RegionLink** nearest = nullptr) const;
};

class RegionMaps
{
 public:
  explicit RegionMaps(const ScanModel& scan = {}, double seed_spacing = 0.25);

  // Takes a new map version: regions whose description did not change keep their fields.
  void set_map(const rgmap::RgMap& map);

  const RegionModel* region(int64_t id) const;
  const std::map<int64_t, std::shared_ptr<const RegionModel>>& regions() const { return regions_; }
  // Follows merges: the region that now stands for `id` (0 if unknown).
  int64_t resolve(int64_t id) const;
  // Region id by name ("" never matches); 0 if none.
  int64_t find_named(const std::string& name) const;
  int64_t version() const { return version_; }
  bool empty() const { return regions_.empty(); }
  size_t bytes() const;

 private:
  ScanModel scan_;
  double seed_spacing_;
  std::map<int64_t, std::shared_ptr<const RegionModel>> regions_;
  std::map<int64_t, int64_t> merged_into_;
  int64_t version_ = -1;
};

}  // namespace rgnav::localizer
