// Region-based Monte Carlo localization in an RG map (diss. 5.3), no LCM.
//
// Every particle lives in one region's frame and is weighed against that region's line map
// (with its neighbours' lines stacked beyond it, region_maps.h). A particle that leaves its
// region (its freespace or the rectangle of its measurements) near a gateway is moved into the
// neighbouring region's frame through the transform the gateway measured and weighed there; the
// estimate crossing a gateway and lying far enough past it is evidence that the robot traversed
// it. Updates are gated by travelled distance / angle. The particle count adapts by KLD
// sampling; resampling is low-variance, when the weights have become uneven. When the
// measurement likelihood falls (augmented MCL) particles are replaced by candidates of a global
// scan-to-region search on the current scan (sensor resetting). The same search starts global
// localization from an unknown pose, which claims a pose only when the views of the robot's
// last metres (view_path.h, each scored in the region holding its place, path_score.h) fit it
// clearly better than every other candidate place (the newest scan search's and, before a
// claim, those of a search of every place and heading on the path, path_search.h), counted on
// the beams both places' maps can judge; when they single out another place than the
// cloud's mode, half the cloud is moved there and the filter decides. A kidnap is flagged when
// the estimate stops explaining the scans or jumps (recovery particles taking over); either way
// the robot is localized globally anew, and a pose is claimed only by the same test.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "geometry/pose2.h"
#include "localizer/global_search.h"
#include "localizer/localizer_options.h"
#include "localizer/region_maps.h"
#include "localizer/scan_model.h"
#include "localizer/view_path.h"
#include "rgmap/rg_map.h"
#include "sensors/laser_scan.h"

namespace rgnav::localizer {

enum class Mode
{
  kNoMap,        // nothing to localize in yet
  kUnknown,      // map, but no pose: global localization starts with the next scan
  kGlobal,       // particles spread over candidate places, not converged
  kTracking,     // converged
};
const char* to_string(Mode m);

// Why global localization has not claimed a pose yet (the newest update's reason; kNone once
// claimed): for diagnostics and the benchmark's trace.
enum class Unsure
{
  kNone,
  kNotConverged,     // no single cluster holds the weight tightly enough
  kShortTravel,      // not yet driven min_travel since the pose became unknown
  kPathElsewhere,    // the views of the path fit best somewhere else than the estimate
  kRival,            // another place explains the views of the path nearly as well
};
const char* to_string(Unsure u);

// The numbers of the newest claim test (Localizer::claim_test): how far the place the views of
// the path single out leads its closest rival, against what it must lead by. For diagnostics
// and the benchmark's trace.
struct ClaimTest
{
  int places = 0;               // places compared (the estimate refined, then its rivals)
  bool best_is_estimate = false;
  double lead = 0;              // the best place's lead over its closest rival (log-likelihood, coarse model) ...
  double margin = 0;            // ... what it had to be
  double lead_all_beams = 0;    // that lead counted on every beam
  int judged_beams = 0;         // beams the lead counted (all of them without claim_judged_beams)
  int beams = 0;                // beams of the path's views
  int views = 0;
  double rival_distance = 0;    // [m] from the best place to that rival, map frame
  double rival_turn_deg = 0;
};

struct Particle
{
  int64_t region = 0;
  geometry::Pose2 pose;   // region_from_base
  double weight = 1.0;    // normalised over the set after every update
};

struct Estimate
{
  bool valid = false;
  int64_t utime = 0;
  int64_t scan_id = 0;
  int64_t region = 0;
  geometry::Pose2 region_from_base;
  geometry::Pose2 map_from_base;
  geometry::Pose2 odom_from_base;        // odometry at utime
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();   // region frame (x, y, theta)
  double cluster_share = 0;              // particle weight within the estimate's cluster
  double inlier_ratio = 0;               // beams the map explains at the estimate
  double confidence = 0;                 // [0, 1] cluster_share * inlier_ratio (0 while not converged)
  bool converged = false;
};

struct GatewayPassed
{
  int64_t utime = 0;
  int64_t gateway = 0;
  int64_t from_region = 0, to_region = 0;
  geometry::Pose2 region_from_base;      // in to_region
  double distance_past = 0;              // [m] from the gateway line
};

struct LocalizerStats
{
  int64_t updates = 0;
  int64_t scans = 0;
  int64_t handovers = 0;                 // estimate moved to a neighbouring region
  int64_t particle_handovers = 0;
  int64_t kidnaps = 0;                   // times the filter declared itself lost
  int64_t global_searches = 0;
  int64_t path_searches = 0;     // whole-path searches before a claim (path_search.h)
  int64_t reassociations = 0;            // cloud moved to an overlapping region that explains the view better
  int64_t recovery_particles = 0;
  int particles = 0;
  double w_slow = 0, w_fast = 0;
};

class Localizer
{
 public:
  explicit Localizer(const LocalizerOptions& options);

  // A new map version. Particles keep their region-frame poses (no jump); a particle whose
  // region was merged away is carried over through the map frame.
  void set_map(const rgmap::RgMap& map);
  // Called as long work goes on (the path search before a claim, region by region): the node
  // reports it on its heartbeat (runtime/node.h note_progress).
  void set_progress(std::function<void()> progress) { progress_ = std::move(progress); }
  // The pose is given (operator, persisted estimate): particles around it with these spreads.
  // False if the region is unknown.
  bool set_pose(int64_t region, const geometry::Pose2& region_from_base, double sigma_xy, double sigma_theta);
  // Resume after a restart: set_pose with the resume spreads; global localization if it does
  // not converge within resume_give_up_updates.
  bool resume(int64_t region, const geometry::Pose2& region_from_base);
  // Forget the pose: global localization from the next scan.
  void start_global();
  // The odometry frame changed (the base driver restarted): the next scan weighs the particles
  // where they are and becomes the new odometry reference; the particles keep their spread.
  void reset_odometry() { odom_at_update_.reset(); }

  // One scan with the odometry pose at its time. Returns true when the filter updated (the
  // travel gate opened, or the first scan of a global localization).
  bool update(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_base);

  Mode mode() const { return mode_; }
  const Estimate& estimate() const { return estimate_; }
  const std::vector<Particle>& particles() const { return particles_; }
  const LocalizerStats& stats() const { return stats_; }
  const RegionMaps& maps() const { return maps_; }
  // No place of the newest global search farther than unique_distance from this pose explains
  // the views of the path (view_path.h, path_score.h) nearly as well as the pose does:
  // what a claim from global localization needs. False outside global localization (no views).
  // The benchmark asks it of the true pose: if false, what the robot saw is ambiguous by the
  // map's own repetition, and staying unsure is the right answer.
  bool distinguishable(int64_t region, const geometry::Pose2& region_from_base) const
  {
    return why_not_distinguishable(region, region_from_base) == Unsure::kNone;
  }
  // What keeps the pose from being distinguishable (kNone if it is). `test`, if given: the
  // pose's lead over its rivals as the claim test counts it (claim_test).
  Unsure why_not_distinguishable(int64_t region, const geometry::Pose2& region_from_base, ClaimTest* test = nullptr) const;
  Unsure unsure() const { return unsure_; }
  const ClaimTest& claim_test() const { return claim_test_; }
  // Set when a kidnap was flagged since the last call.
  bool take_kidnap_flag();
  std::vector<GatewayPassed> take_gateway_events();

 private:
  // Particles around the best candidates of a global search on this scan.
  void seed_global(const std::vector<Eigen::Vector2d>& points, size_t count, std::vector<Particle>* out);
  void move_particles(const geometry::Pose2& delta);
  void hand_over(Particle* p);
  std::vector<double> weigh(const std::vector<Eigen::Vector2d>& points, double* mean_beam_likelihood);
  void estimate_from(const std::vector<double>& weights, const std::vector<Eigen::Vector2d>& points);
  void resample(const std::vector<double>& weights, const std::vector<Eigen::Vector2d>& points, double w_avg);
  void weigh_estimate_resample(const std::vector<Eigen::Vector2d>& points);
  // The lightest `share` of the particles replaced by search candidates (no resampling).
  void replace_lightest(const std::vector<Eigen::Vector2d>& points, double share);
  const RegionLink* link_between(int64_t here, int64_t there) const;
  void reassociate(const std::vector<Eigen::Vector2d>& points);
  // The pose refined on the views of the path, then the newest search's distinct places refined
  // the same way (the pose first; scores on the views).
  // `path_rivals` (places of a whole-path search, path_search.h) are checked before the newest
  // search's.
  std::vector<Hypothesis> path_places(int64_t region, const geometry::Pose2& region_from_base,
                                      const std::vector<Hypothesis>& path_rivals) const;
  // The best distinct places of a search of every place and heading on the views of the path.
  std::vector<Hypothesis> search_path_rivals() const;
  bool same_place(const Hypothesis& a, const Hypothesis& b) const;
  // What the best place must lead by on the evidence of this many views.
  double path_margin(double views) const;
  // Why the estimate cannot be claimed yet (kNone: it can); `elsewhere` is set to the place the
  // path singles out when that is not the estimate.
  Unsure claim_check(std::optional<Hypothesis>* elsewhere);
  // The same for given places (path_places: the estimate first).
  Unsure path_verdict(const std::vector<Hypothesis>& places, std::optional<Hypothesis>* elsewhere, ClaimTest* test) const;
  // How far places[c] leads every other distinct place: the weakest of those leads (or the first
  // below the margin), on the beams both maps can judge (all beams without claim_judged_beams).
  ClaimTest lead_of(const std::vector<Hypothesis>& places, size_t c) const;
  // Half the cloud replaced by particles around `place` (the lightest go).
  void inject_at(const Hypothesis& place);
  // The estimate moved farther than odometry says the robot did since the update before.
  bool jumped() const;
  void track_region_change();
  // True when the estimate has not explained the scans for kidnap_after_s.
  bool kidnapped(const std::vector<Eigen::Vector2d>& points, const geometry::Pose2& odom_from_base);
  std::optional<geometry::Pose2> in_frame_of(int64_t region, const Particle& p) const;

  LocalizerOptions options_;
  RegionMaps maps_;
  BeamScorer scorer_;
  std::mt19937_64 rng_;
  Mode mode_ = Mode::kNoMap;
  Unsure unsure_ = Unsure::kNone;
  ClaimTest claim_test_;                  // of the newest claim_check
  std::vector<Particle> particles_;
  Estimate estimate_;
  LocalizerStats stats_;
  std::optional<geometry::Pose2> odom_at_update_;
  int64_t utime_ = 0, scan_id_ = 0;
  int64_t low_inlier_since_ = 0;   // utime of the first scan of the current low-inlier run, 0 if none
  int64_t last_region_ = 0;
  int updates_since_pose_given_ = 0;
  bool resuming_ = false;
  double global_travel_ = 0;              // [m] driven since global localization started
  double inlier_usual_ = -1;        // slow average of the estimate's inlier share, -1 = none yet
  std::vector<Hypothesis> last_search_;   // candidates of the newest global search
  ViewPath views_;                        // views since global localization started
  std::vector<Hypothesis> path_rivals_;   // places of the newest whole-path search, moved along by odometry
  std::function<void()> progress_;        // set_progress
  double path_rivals_travel_ = -1;        // global_travel_ at that search (-1: none yet)
  std::optional<Estimate> previous_;      // the estimate of the update before, for the jump check
  bool kidnap_flag_ = false;
  // Gateway traversal evidence: the estimate entered `to` from `from` through `gateway`.
  struct PendingPass { int64_t gateway = 0, from = 0, to = 0; };
  std::optional<PendingPass> pending_pass_;
  std::vector<GatewayPassed> passed_;
};

}  // namespace rgnav::localizer
