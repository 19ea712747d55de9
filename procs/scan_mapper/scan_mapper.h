// The scan mapper (no LCM): incremental scan-matching SLAM after Gutmann & Konolige's local
// registration / global correlation, as the dissertation's ScanMapper (sec. 5.2).
//
//  1. Gating: a scan is accepted once the robot travelled min_travel_m or turned
//     min_rotation_rad since the last accepted scan (odometry interpolated at scan time).
//  2. Local registration: point-to-line ICP with a decaying rejection threshold against a
//     point map of the last local_map_scans accepted scans, started at the odometry guess;
//     if it fits badly, a correlative search around the guess re-seeds ICP. Every scan's
//     surface normals are oriented toward its laser, and only points seen from the same side
//     pair: the two faces of a thin wall (room side, corridor side) stay apart. Points on
//     something that moved (another scan of the local map saw through them: a person walking
//     along a hallway, whose trail would otherwise pull the match along it) are then left out
//     and ICP runs again from its fit (moving_points.h).
//  3. Kalman fusion: the scan-matched increment and the odometry increment are combined
//     weighted by their covariances (in a corridor ICP is weak along it; odometry is not).
//     Odometry's translation scale is learned from the matches that hold both directions
//     and taken out of every increment first, so that a hallway's axis, left to odometry, is
//     not a percent long (odometry_scale.h).
//  4. Global correlation: every few scans, an older scan whose relative uncertainty (read off
//     the graph, loop_search.h) allows it to be here is searched with the correlative matcher
//     over a window of that uncertainty (a submap around it) and verified with ICP (enough
//     inliers, surface residuals near the range noise: a worse fit matched the wrong structure
//     and its covariance would lie about it). The
//     hypothesis is accepted alone only where the graph knows the relative pose well;
//     elsewhere it waits for a hypothesis from a later scan that agrees with it (pairwise
//     consistency). Accepted closures become robust edges of the pose graph, which is
//     re-optimised; a batch left inconsistent after optimising is removed again, and so is
//     one the rest of the graph had to bend for (its strain: the rise in cost of the edges
//     that were there before). In a row of equal rooms a look-alike fits its own edge and
//     even agrees with its neighbours' hypotheses; only the odometry chain shows it false.
// Algorithms run on message time only; the same inputs give the same map.
//
// The optimisation is the one step that can take long (hundreds of ms on a large graph). By
// default it runs inside add_scan (deterministic: offline tools, tests). With
// set_deferred_optimization(true) add_scan instead leaves an OptimizationJob (a copy of the
// graph with the new closures) for the caller to run on another thread, and keeps adding
// scans meanwhile; apply_optimization() then adopts the result: the optimised poses for the
// nodes the job knew, and the nodes added since moved rigidly with the newest of those.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <list>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scan_mapper/correlative_matcher.h"
#include "scan_mapper/loop_search.h"
#include "scan_mapper/odometry_buffer.h"
#include "scan_mapper/odometry_scale.h"
#include "scan_mapper/optimization_job.h"
#include "scan_mapper/point_map.h"
#include "scan_mapper/pose_graph.h"
#include "scan_mapper/scan_mapper_options.h"

namespace rgnav::scan_mapper {

// One accepted scan.
struct ScanNode
{
  sensors::LaserScan scan;
  Pose2 odom_from_base;      // raw odometry at scan time
  Pose2 map_from_base;       // current estimate
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  int revision = 0;          // +1 every time the estimate is corrected after publication
  Pose2 published;           // estimate at the last (re)publication
  double path_m = 0.0;       // odometry path length from the first node
  Points points;             // thinned scan points in the base frame
  Points normals;            // their surface normals (base frame, toward the laser), computed once
  std::vector<char> has_normal;
};

struct MapperUpdate
{
  bool accepted = false;
  int node = -1;                 // index of the new node
  bool matched = false;          // scan matching contributed (not odometry alone)
  bool loop_closed = false;
  std::vector<int> corrected;    // earlier nodes whose estimate changed (revision bumped)
  bool optimization_ready = false;  // deferred mode: take_optimization_job() has a job
};

struct MapperStats
{
  int64_t scans_in = 0, accepted = 0, no_odometry = 0, matched = 0, correlative_retries = 0,
          match_rejected = 0, loop_attempts = 0, loop_closures = 0, loop_rejected_after_opt = 0, invalid = 0;
  int64_t loop_rejected_strain = 0;  // of loop_rejected_after_opt: for the strain on the graph
  int64_t loop_ambiguous = 0;        // loop searches whose best fit had a near-equal rival elsewhere
  int64_t loop_pruned = 0;           // closures taken out later, when the graph disagreed (OptimizationJob)
  int64_t moving_points = 0;  // points left out of local registration as seen through
  int64_t turns_held = 0;     // fits whose turn the scan did not hold: odometry's heading kept
  int64_t axes_held = 0;      // fused fits whose weakest direction too few surface points held: odometry's there
  double odometry_trans_scale = 1.0;  // learned scale on the translation sigmas (OdometryNoise::adapt_*)
  double odometry_scale = 1.0;        // learned odometry translation scale (true / odometry; odometry_scale.h)
};

// Everything needed to resume: nodes and graph edges.
struct MapperState
{
  std::vector<ScanNode> nodes;
  std::vector<PoseGraphEdge> edges;
};

class ScanMapper
{
 public:
  explicit ScanMapper(ScanMapperOptions options);
  // Resumes from a persisted state. Odometry after a restart may have a new origin: the
  // first scan is accepted at the last estimate and relocalised with a wide search.
  ScanMapper(ScanMapperOptions options, MapperState state);

  void add_odometry(const OdometrySample& sample);
  // The odometry source restarted (new origin): relocalise the next scan like after a restart.
  void reset_odometry();
  // Inputs failing input_checks.h are refused (counted in stats().invalid).
  MapperUpdate add_scan(const sensors::LaserScan& scan);

  void set_deferred_optimization(bool deferred) { deferred_ = deferred; }
  // Called between the steps of a scan's work (registration, a correlative search, a loop
  // closure's submap and search): under load one scan can take seconds, and the node's
  // progress counter shows the supervisor that the process is working, not hung.
  void set_progress(std::function<void()> progress) { progress_ = std::move(progress); }
  // Deferred mode: the job left by the last add_scan (once). No closure is searched while a
  // job is out; the caller must hand each job back with apply_optimization or cancel it.
  std::optional<OptimizationJob> take_optimization_job();
  bool optimization_in_flight() const { return in_flight_; }
  // Adopts a finished job (loop_closed and corrected say what changed; all nodes had been
  // published, so every node that moved enough is in corrected).
  MapperUpdate apply_optimization(const OptimizationJob& done);
  void cancel_optimization() { in_flight_ = false; }

  const std::vector<ScanNode>& nodes() const { return nodes_; }
  const ScanMapperOptions& options() const { return options_; }
  const MapperStats& stats() const { return stats_; }
  MapperState state() const;
  const PoseGraph& graph() const { return graph_; }

  // Newest estimate and the correction from odometry into the map frame at that scan.
  std::optional<Pose2> current_pose() const;
  std::optional<Pose2> map_from_odom() const;

 private:
  struct Submap
  {
    std::unique_ptr<LikelihoodGrid> grid;
    std::unique_ptr<PointMap> points;
  };

  MapperUpdate process(const sensors::LaserScan& scan, const Pose2& odom);
  void note_progress() const
  {
    if (progress_) progress_();
  }
  void prepare_points(ScanNode* node) const;
  // The node's surface normals, oriented toward its laser.
  void compute_normals(ScanNode* node) const;
  // With the translation sigmas scaled by trans_scale.
  Eigen::Matrix3d odometry_covariance(const Pose2& increment, double trans_scale) const;
  // Updates the learned translation noise scale from a fused match's innovation (the
  // increments' difference, in the previous node's frame) and its covariance R.
  void learn_odometry_noise(const Pose2& increment, const Eigen::Vector3d& innovation, const Eigen::Matrix3d& R);
  // The ICP options with icp.degenerate_min_points for the odometry as learned so far
  // (OdometryNoise::adapt_degeneracy).
  IcpOptions fit_options() const;
  // Registers the scan's points (base frame) against the local map from guess: the acceptable
  // fits, best first (the fit from guess and, when it was poor, a correlative search's); none if
  // registration fails. A fit turned from guess by more than turn_check_sigmas x
  // odometry_sigma_rot [rad] that fits little better than guess's heading does is replaced by
  // the translation-only fit at guess's heading (ScanMapperOptions::turn_check_sigmas).
  std::vector<IcpResult> register_locally(const ScanNode& scan, const Pose2& guess, bool wide,
                                          double odometry_sigma_rot, const IcpOptions& icp);
  // Registers again from map_from_scan without the points on something that moved (seen through,
  // moving_points.h); nullopt when there were none (or too few points were left).
  std::optional<IcpResult> register_without_moving(const ScanNode& scan, const PointMap& map, const Pose2& map_from_scan,
                                                   const IcpOptions& icp);
  // Searches one closure for `node`; nullopt when none is found.
  std::optional<ClosureHypothesis> find_closure(int node);
  bool try_loop_closure(int node, MapperUpdate* update);
  const Submap& submap_around(int anchor);
  // unpublished: a node not published yet (its estimate is taken as is), or -1.
  void collect_corrections(MapperUpdate* update, int unpublished);
  // Checks the closures of an optimised job and, if they hold, adopts its poses.
  bool adopt(const OptimizationJob& job, MapperUpdate* update, int unpublished);

  const ScanMapperOptions options_;
  OdometryBuffer odometry_;
  std::vector<ScanNode> nodes_;
  PoseGraph graph_;
  MapperStats stats_;
  bool relocalize_next_ = false;
  double innovation_ratio_ = 1.0;  // running mean normalised translation innovation (per axis) ...
  int64_t innovation_samples_ = 0;  // ... of this many matches (a plain mean until the window is full)
  OdometryScale odometry_scale_;    // learned from the same matches; not persisted (learned again)
  int since_loop_try_ = 0;
  std::map<int, Submap> submaps_;   // by anchor node; small LRU
  std::list<int> submap_lru_;
  std::vector<ClosureHypothesis> pending_;  // closures waiting for a consistent witness
  bool deferred_ = false;
  bool in_flight_ = false;
  std::function<void()> progress_;          // set_progress
  std::optional<OptimizationJob> job_;      // deferred: made, not yet taken
};

}  // namespace rgnav::scan_mapper
