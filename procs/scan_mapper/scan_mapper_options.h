// Every parameter of the scan mapper, with defaults; loaded and validated from the
// `scan_mapper:` section of config/scan_mapper.yaml (see load_scan_mapper_options).
#pragma once

#include "config/config.h"
#include "config/robot_description.h"
#include "scan_mapper/correlative_matcher.h"
#include "scan_mapper/icp.h"
#include "scan_mapper/loop_search.h"
#include "scan_mapper/moving_points.h"
#include "scan_mapper/odometry_scale.h"
#include "scan_mapper/pose_math.h"
#include "scan_mapper/pose_graph.h"
#include "scan_mapper/scan_normals.h"
#include "scan_mapper/scan_points.h"

namespace rgnav::scan_mapper {

struct OdometryNoise
{
  // Standard deviations of one odometry increment: grow with the distance and turn.
  double trans_per_m = 0.1;        // [m/m]
  double rot_per_rad = 0.1;        // [rad/rad]
  double rot_per_m = 0.05;         // [rad/m]
  double min_trans_m = 0.01;       // floor
  double min_rot_rad = 0.01;       // floor
  // The translation sigmas above describe good odometry; a robot's own is learned from the scan
  // matches: the mean normalised translation innovation of well-constrained matches (expected 1
  // per axis for a consistent filter) over about adapt_window_scans scans scales the
  // translation variance, between 1 and max_scale^2. A too loose model lets loop closures slide
  // the graph along a hallway: such a closure holds only across the hallway, and where the two
  // passes' hallway directions differ by a fraction of a degree, the optimiser eases that
  // tension by sliding the loosely held chain along the axis (a 70 m hallway, 0.01 m + 0.1 m/m for an
  // odometry good to ~1 %: 0.1-0.9 m per closure, 8 m over a 40 m drive that odometry alone got
  // within 0.4 m). A too tight model trusts a poor odometry over the scans (a real log's poor odometry: learned 2.3).
  // Not persisted: after a restart it is learned again. 0: off.
  int adapt_window_scans = 0;
  double adapt_max_scale = 4.0;
  // The learned scale s also sets how many surface points hold a fit's weakest direction well
  // enough to be trusted there over odometry: icp.degenerate_min_points / s^2, in local
  // registration and loop closures alike. The count stands for the fit's information along that
  // direction, and odometry's there is 1 / (s sigma)^2: against an odometry s times poorer, a
  // fit held by s^2 times fewer points is worth as much. The sims' odometry learns s = 1 and
  // keeps the threshold; a real log with poor odometry learns 2.5, where the fixed count of 60 left 42 %
  // of its steps, ordinary rooms among them, to an odometry that poor: agreement with the
  // reference 0.074 -> 0.049 m. It needs ScanNormalOptions' beam normals: without them, sparse
  // wall samples pairing point-to-point gave a hallway's fits a few dozen points of false hold
  // along the axis, and trusted there they made the fits short (scan_normals.h).
  bool adapt_degeneracy = false;
};

struct LoopClosureOptions
{
  bool enabled = true;
  int every_n_scans = 5;           // try a closure every n accepted scans (every scan while one waits)
  int min_node_gap = 30;           // a candidate is at least this many accepted scans back
  double min_path_gap_m = 5.0;     // ... and this far back along the path
  double search_radius_m = 4.0;    // candidates within this distance of the current estimate
                                   // plus the search window (which grows with the uncertainty)
  int submap_half_nodes = 10;      // submap = candidate's neighbours within +- this many scans
  double submap_radius_m = 12.0;   // submap points farther from its anchor are dropped
  DriftModel drift;                // how fast the relative uncertainty grows along the graph
  double gate_sigmas = 3.0;        // window = this many standard deviations of that uncertainty
  double window_base_m = 0.5;      // ... clamped to [base, max]
  double window_max_m = 3.0;
  double angular_window_base_rad = 0.15;
  double angular_window_max_rad = 0.5;
  double min_score = 0.6;          // correlative score needed to try ICP
  // A second fit at least ambiguity_distance_m from the best scoring this share of the best
  // makes the match ambiguous (doors at regular spacing along a hallway): no hypothesis.
  // 1 (or more): off.
  double max_ambiguity = 0.95;
  double ambiguity_distance_m = 1.0;
  double min_inlier_ratio = 0.75;  // ICP agreement needed to accept
  double max_rms_m = 0.02;         // ... and ICP rms surface residual allowed (about twice the range noise)
  // Verification: a hypothesis is accepted alone only where the graph already knows the
  // relative pose well (sigma below direct_max_sigma_m and innovation chi2 below
  // direct_max_chi2); otherwise it waits until a hypothesis from a later scan (within
  // confirm_within_nodes) agrees with it within the consistency tolerance.
  double direct_max_sigma_m = 0.25;
  double direct_max_chi2 = 9.0;
  int confirm_within_nodes = 30;
  // A witness must be found from a scan at least this far along the path [m] from the one whose
  // hypothesis it confirms (loop_search.h, witnesses). The next scan, a step on (or turned on the
  // spot), sees the place as the first did and fits a look-alike of it just as well: with both
  // counted, a look-alike room seen from one spot confirmed itself, and such closures
  // (consecutive scans, one anchor, 1-4 m off across the fit's held direction) broke maps of
  // generated buildings whose loops were long enough that the chain bent for them within
  // max_strain_chi2 (100 buildings, one lap each: 6 maps broken -> 0). The hypotheses a waiting
  // one gathers meanwhile stay pending and may be confirmed with it: a hallway's repeated
  // matches then count several times, which degenerate_keeps_graph_axis and
  // degenerate_covariance_scale must absorb (without them, 0.6 -> 2 m along a hallway). 0: off.
  double witness_min_travel_m = 1.0;
  ConsistencyTolerance consistency;
  double max_residual_chi2 = 25.0; // after optimising, a closure this inconsistent is removed
  // ... and so is a batch that strains the rest of the graph: the cost of the edges it did
  // not add rises by more than this per closure (chi2). A look-alike place (a row of equal
  // rooms) fits its closure edge perfectly; it is the odometry chain that must bend for it.
  double max_strain_chi2 = 100.0;
  // A batch that holds also takes out earlier closures the optimised graph disagrees with by
  // more than max_residual_chi2 (OptimizationJob::prune_earlier).
  bool prune_earlier_closures = false;
  double covariance_scale = 4.0;   // loop edges are trusted less than sequential ones
  // Variance [m^2] (before covariance_scale) a loop closure's match gets along a direction held
  // by fewer than icp.degenerate_min_points surface points. Larger than the sequential matches'
  // icp.degenerate_variance_m2: along a hallway every scan of a long drive "closes" to the same
  // stretch, and 20 such edges, however weak each, add up to a pull of metres (a long hallway of cubicles).
  double degenerate_variance_m2 = 1.0;
  // Along that direction the fit measures nothing: where it ends up there is where the search
  // happened to stop. Such a closure then keeps the graph's relative pose along the direction and
  // corrects only across it and the heading (find_closure). With the variance alone, the
  // return pass down a 70 m hallway was pushed on at closure after closure, 4 m in all
  // (one lap; bench slam's truth_pairs.txt, online estimate); with the axis kept, 1.9 m; with
  // the scale below too, 0.06 m (relation error 1.43 -> 0.045 m).
  bool degenerate_keeps_graph_axis = false;
  // ... and its covariance is scaled by this on top of covariance_scale. Along a hallway the
  // closures come every few scans against the same two walls, so their errors across the axis
  // and in heading are one error repeated, not independent ones; weighed as independent they
  // still bent the chain. Both together, on a building with a 70 m hallway: 0.099 -> 0.019 m relation error over three
  // seeds. Alone, each did less (the test HallwayClosuresKeepTheGraphsAxisAndCountAsOneWitness:
  // 1.56 m as measured, 2.08 axis kept, 0.61 scaled, 0.52 both).
  double degenerate_covariance_scale = 1.0;
  double point_spacing_m = 0.1;    // thinner scans for the correlative search
  // Coarser than local registration: the window is large and ICP refines afterwards.
  CorrelativeOptions correlative{0.1, 0.1, 4, 2.0};
};

struct ScanMapperOptions
{
  Pose2 base_from_laser;           // laser mounting pose (robot description)
  double min_travel_m = 0.2;       // accept a scan after this much travel ...
  double min_rotation_rad = 0.17;  // ... or this much rotation since the last accepted one
  int64_t max_odometry_extrapolation_us = 100'000;  // hold the newest odometry this long
  PointFilterOptions points;
  ScanNormalOptions normals;       // which points pair point-to-line
  int local_map_scans = 15;        // recent accepted scans registered against
  IcpOptions icp;
  MovingPointOptions moving_points;  // left out of local registration
  double min_inlier_ratio = 0.5;   // below: retry with the correlative search
  double min_accept_inlier_ratio = 0.25;  // below even after the retry: odometry alone
  CorrelativeWindow local_window{0.4, 0.35};  // correlative retry around the odometry guess
  CorrelativeOptions correlative;
  double max_innovation_chi2 = 1000.0;  // scan match vs odometry disagreement that rejects the match
  // A fit turned from odometry's heading by more than this many of odometry's heading sigmas must
  // explain more of the scan than the best fit at odometry's heading (translation only) by at
  // least turn_min_inlier_gain (inlier ratio), else the heading is odometry's. A round bay seen
  // from its door is an arc that fits any heading; turning it to where the local map's arc ends
  // gains a few inliers, and the Hessian, held by the jambs, claimed 0.25 deg for fits 15-20 deg
  // off (issue 6: a room entered from a long hallway). 0: off.
  // Such a turned fit must also fit the surfaces about as precisely as odometry's heading does:
  // surface rms at most turn_max_rms_ratio x the held fit's. A turn bought with inliers at the
  // 10 cm scale fits the arc at twice the range noise (20 deg turns passed the inlier
  // test with 0.022 m against 0.010 m at odometry's heading). 0: off.
  double turn_check_sigmas = 3.0;
  double turn_min_inlier_gain = 0.05;
  double turn_max_rms_ratio = 1.25;
  OdometryNoise odometry_noise;
  OdometryScaleOptions odometry_scale;
  LoopClosureOptions loop;
  OptimizerOptions optimizer;
  double republish_min_change_m = 0.005;     // corrections smaller than this are not republished
  double republish_min_change_rad = 0.002;
};

// The laser mounting pose is the robot description's (laser_front.base_from_laser).
ScanMapperOptions load_scan_mapper_options(const config::Config& section, const config::RobotDescription& robot);

}  // namespace rgnav::scan_mapper
