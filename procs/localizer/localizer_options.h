// Parameters of the region-based Monte Carlo localizer (diss. 5.3), as config/localizer.yaml
// names them. Defaults are the values documented there.
#pragma once

#include <string>

#include "geometry/pose2.h"

namespace rgnav::config { class Config; struct RobotDescription; }

namespace rgnav::localizer {

// Odometry error model (sample_motion_model_odometry in the form of the simulator's error model:
// a relative error plus a random walk that grows with the square root of the distance / angle).
struct MotionNoise
{
  double translation_per_m = 0.03;       // std of the distance error per metre driven (relative)
  double translation_per_sqrt_m = 0.02;  // [m/sqrt(m)] random walk of the distance
  double rotation_per_rad = 0.05;        // std of the turn error per radian turned (relative)
  double rotation_per_sqrt_rad = 0.03;   // [rad/sqrt(rad)]
  double rotation_per_m = 0.01;          // [rad/m] heading error while driving straight (relative)
  double rotation_per_sqrt_m = 0.01;     // [rad/sqrt(m)]
  double lateral_per_m = 0.01;           // std of the sideways error per metre driven
};

// Likelihood-field measurement model (Thrun et al., Probabilistic Robotics 6.4).
struct ScanModel
{
  int beams = 60;                  // beams used per update, evenly over the scan
  double min_range = 0.3;          // [m] shorter returns are something touching the robot, not the map
  double sigma = 0.08;             // [m] hit noise around the line map
  double z_hit = 0.9;              // weight of the Gaussian term
  double z_rand = 0.1;             // weight of the uniform term (people, furniture, clutter)
  double max_distance = 1.0;       // [m] distance field saturates here
  double field_resolution = 0.04;  // [m] cell edge of the distance field
  double field_margin = 1.0;       // [m] field reaches this far beyond the line map
  // Beams are not independent (neighbours see the same wall): the log-likelihood of a scan is
  // scaled by this before it becomes a weight, so that one scan cannot collapse the cloud.
  double beam_weight = 0.5;
  double inlier_distance = 0.15;   // [m] a beam within this of a line is explained by the map
};

struct ParticleCount
{
  int min = 300;
  int max = 4000;
  double kld_epsilon = 0.05;       // KLD sampling: bound on the error of the posterior
  double kld_z = 2.326;            // upper quantile of N(0,1) for 1 - delta = 0.99
  double bin_xy = 0.25;            // [m] histogram bins for KLD
  double bin_theta_deg = 10.0;
  double resample_ess_ratio = 0.5; // resample when the effective sample size falls below this share
};

struct GlobalOptions
{
  double cell = 0.25;              // [m] candidate positions: freespace cells thinned to this spacing
  int headings = 36;               // candidate headings per position
  int beams = 30;                  // beams used by the exhaustive search
  double sigma = 0.2;              // [m] broader hit noise for the coarse search
  int hypotheses = 300;            // best candidates kept (one per position)
  int particles = 6000;            // particles seeded around them
  double seed_xy = 0.15;           // [m] spread of the seeded particles around a candidate
  double seed_theta_deg = 6.0;
  double reseed_share = 0.1;       // share of particles re-seeded from a new search per update while unsure
  double beam_weight = 0.2;        // ScanModel::beam_weight while unsure (softer: no early decision)
  double min_travel = 1.0;         // [m] driven (a turn of 1 rad counts 0.5 m) before the pose counts as found ...
  double unique_distance = 2.0;    // [m] ... and no place farther than this from it ...
  double unique_margin = 3.0;      // ... explains the views of the path (view_path.h) within this times sqrt(views) (log-likelihood, coarse model)
  int rivals = 16;                 // distinct places (unique_distance apart) of the newest search checked against the estimate
  double view_spacing = 0.5;       // [m] travel between the views kept for that test
  double view_path_length = 4.0;   // [m] travel back the views reach (odometry drift grows with it)
  // Before a claim, every place and heading of the map is matched against the views of the path
  // (path_search.h), and its best `path_search_places` distinct places must lose by the margin
  // too (false: only the newest scan search's `rivals`).
  bool claim_path_search = true;
  int path_search_places = 8;
  // ... and it must win on the beams both places' maps can judge (near a line or in the freespace
  // their scans carved), not on a wall one map lacks (false: on all beams).
  bool claim_judged_beams = true;
  // A beam is judged in the freespace of the stacked map: the region's and, outside the region's
  // own rectangle, its neighbours' beyond the gateways, where the field stacks their lines
  // (false: the region's own freespace only). Off: more right claims, but more wrong ones on a
  // floor of turned copies (procs/localizer/README.md).
  bool judged_through_gateways = false;
};

struct RecoveryOptions
{
  double alpha_slow = 0.005;       // augmented MCL: long-term average of the measurement likelihood
  double alpha_fast = 0.1;         // short-term average
  double max_share = 0.1;          // at most this share of particles replaced per update
  double kidnap_inlier_ratio = 0.5;  // estimate explains fewer beams than this ...
  double kidnap_drop = 0.7;        // ... and below this share of its usual value ...
  double usual_alpha = 0.003;      // (the usual value: average over scans with this weight, ~5 s at 75 Hz)
  double kidnap_after_s = 1.0;     // ... for this long (message time): kidnapped, re-localize
  double kidnap_jump = 1.0;        // [m] an estimate jumping this much farther than odometry moved is a kidnap too
};

struct EstimateOptions
{
  double cluster_xy = 0.5;         // [m] particles this close to the best one form the estimate ...
  double cluster_theta_deg = 20.0; // ... if their heading is this close too
  double converged_xy = 0.2;       // [m] cluster spread (1 sigma) below this ...
  double converged_theta_deg = 5.0;   // ... and this, holding min_cluster_share of the weight
  double min_cluster_share = 0.6;
};

struct LocalizerOptions
{
  geometry::Pose2 base_from_laser{0.12, 0, 0};
  double update_distance = 0.1;     // [m] filter update after this much travel ...
  double update_angle_deg = 5.0;    // ... or this much turning
  MotionNoise motion;
  ScanModel scan;
  ParticleCount count;
  GlobalOptions global;
  RecoveryOptions recovery;
  EstimateOptions estimate;
  double handover_reach = 1.5;      // [m] particles leave a region only this close to one of its gateways ...
  double handover_bbox_margin = 0.3;  // [m] ... when off its freespace or this far outside its measurement rectangle
  double gateway_passed_distance = 0.5;  // [m] estimate this far past a gateway: it was traversed
  double initial_xy = 0.1;          // [m] spread of a given start pose (operator, persisted estimate)
  double initial_theta_deg = 5.0;
  double resume_xy = 0.3;           // [m] spread of the persisted estimate after a restart
  double resume_theta_deg = 10.0;
  int resume_give_up_updates = 15;  // not converged after this many updates: global localization
  uint64_t seed = 1;
};

struct LocalizerChannels
{
  std::string rg_map = "RG_MAP";
  std::string laser = "LASER_FRONT";
  std::string odometry = "ODOMETRY";
  std::string request = "LOCALIZE_REQUEST";
  std::string pose = "POSE";
  std::string gateway_passed = "LOCALIZER_GATEWAY_PASSED";
};

struct LocalizerNodeOptions
{
  LocalizerChannels channels;
  LocalizerOptions localizer;
  double max_scan_age = 0.5;        // [s] a scan older than this against odometry is dropped
  double persist_period = 1.0;      // [s] message time between saves of the estimate
};

// Reads the config's `localizer`, `channels` and `node` sections; the laser mount comes from the
// robot description. Throws config::ConfigError naming file and key.
LocalizerNodeOptions load_localizer_options(const config::Config& root, const config::RobotDescription& robot);

}  // namespace rgnav::localizer
