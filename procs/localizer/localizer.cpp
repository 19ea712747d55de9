#include "localizer/localizer.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include "geometry/segment2.h"
#include "localizer/motion_model.h"
#include "localizer/path_score.h"
#include "localizer/path_search.h"
#include "localizer/resampling.h"

namespace rgnav::localizer {

using Eigen::Vector2d;
using geometry::normalize_angle;
using geometry::Pose2;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr size_t kMinPoints = 5;   // fewer returns than this say nothing about the pose
// Another region takes the cloud over only if it explains this many times more beams.
constexpr double kReassociateGain = 1.5;
// A turn shows the surroundings anew as driving does: 1 rad counts as this much travel.
constexpr double kTurnAsTravel = 0.5;   // [m/rad]

uint64_t bin_key(const Particle& p, const ParticleCount& o)
{
  const auto q = [](double v, double step) { return static_cast<uint64_t>(static_cast<int64_t>(std::floor(v / step)) & 0xFFFF); };
  return (static_cast<uint64_t>(p.region) << 48) ^ (q(p.pose.x(), o.bin_xy) << 32) ^ (q(p.pose.y(), o.bin_xy) << 16) ^
         q(p.pose.theta(), o.bin_theta_deg * kDeg);
}

}  // namespace

const char* to_string(Mode m)
{
  switch (m) {
    case Mode::kNoMap: return "no map";
    case Mode::kUnknown: return "pose unknown";
    case Mode::kGlobal: return "global localization";
    case Mode::kTracking: return "tracking";
  }
  return "?";
}

const char* to_string(Unsure u)
{
  switch (u) {
    case Unsure::kNone: return "none";
    case Unsure::kNotConverged: return "not converged";
    case Unsure::kShortTravel: return "short travel";
    case Unsure::kPathElsewhere: return "path fits elsewhere";
    case Unsure::kRival: return "rival";
  }
  return "?";
}

Localizer::Localizer(const LocalizerOptions& options)
    : options_(options),
      maps_(options.scan, options.global.cell),
      scorer_(options.scan.sigma, options.scan.z_hit, options.scan.z_rand, options.scan.max_distance),
      rng_(options.seed),
      views_(options.global.view_spacing, options.global.view_path_length, kTurnAsTravel)
{
}

void Localizer::set_map(const rgmap::RgMap& map)
{
  std::map<int64_t, Pose2> old_frames;
  for (const auto& [id, r] : maps_.regions()) old_frames[id] = r->map_from_region;
  maps_.set_map(map);
  // A particle whose region was merged away goes to the surviving region through the map frame.
  std::vector<Particle> kept;
  kept.reserve(particles_.size());
  for (auto p : particles_) {
    if (!maps_.region(p.region)) {
      const int64_t r = maps_.resolve(p.region);
      const auto old = old_frames.find(p.region);
      if (r == 0 || old == old_frames.end()) continue;
      p.pose = maps_.region(r)->map_from_region.inverse() * old->second * p.pose;
      p.region = r;
    }
    kept.push_back(p);
  }
  particles_ = std::move(kept);
  if (estimate_.valid && !maps_.region(estimate_.region)) {
    const int64_t r = maps_.resolve(estimate_.region);
    const auto old = old_frames.find(estimate_.region);
    if (r != 0 && old != old_frames.end()) {
      estimate_.region_from_base = maps_.region(r)->map_from_region.inverse() * old->second * estimate_.region_from_base;
      estimate_.region = r;
    } else {
      estimate_.valid = false;
    }
  }
  if (estimate_.valid) estimate_.map_from_base = maps_.region(estimate_.region)->map_from_region * estimate_.region_from_base;
  last_region_ = estimate_.valid ? estimate_.region : 0;
  pending_pass_.reset();
  if (maps_.empty()) {
    mode_ = Mode::kNoMap;
    particles_.clear();
  } else if (mode_ == Mode::kNoMap || particles_.empty()) {
    start_global();
  }
}

bool Localizer::set_pose(int64_t region, const Pose2& region_from_base, double sigma_xy, double sigma_theta)
{
  const int64_t r = maps_.resolve(region);
  if (r == 0) return false;
  std::normal_distribution<double> n01(0.0, 1.0);
  const size_t n = static_cast<size_t>(std::max(options_.count.min, options_.count.max / 2));
  particles_.assign(n, Particle{});
  for (auto& p : particles_) {
    p.region = r;
    p.weight = 1.0 / static_cast<double>(n);
    p.pose = Pose2(region_from_base.x() + sigma_xy * n01(rng_), region_from_base.y() + sigma_xy * n01(rng_),
                   region_from_base.theta() + sigma_theta * n01(rng_));
  }
  mode_ = Mode::kTracking;
  unsure_ = Unsure::kNone;
  estimate_ = Estimate{};
  estimate_.valid = true;
  estimate_.region = r;
  estimate_.region_from_base = region_from_base;
  estimate_.map_from_base = maps_.region(r)->map_from_region * region_from_base;
  last_region_ = r;
  pending_pass_.reset();
  odom_at_update_.reset();   // the next scan weighs the particles where they are
  low_inlier_since_ = 0;
  inlier_usual_ = -1;
  previous_.reset();
  views_.clear();
  updates_since_pose_given_ = 0;
  resuming_ = false;
  return true;
}

bool Localizer::resume(int64_t region, const Pose2& region_from_base)
{
  if (!set_pose(region, region_from_base, options_.resume_xy, options_.resume_theta_deg * kDeg)) return false;
  resuming_ = true;
  return true;
}

void Localizer::start_global()
{
  particles_.clear();
  mode_ = maps_.empty() ? Mode::kNoMap : Mode::kUnknown;
  unsure_ = Unsure::kNotConverged;
  estimate_.valid = false;
  estimate_.converged = false;
  estimate_.confidence = 0;
  last_region_ = 0;
  pending_pass_.reset();
  resuming_ = false;
  low_inlier_since_ = 0;
  inlier_usual_ = -1;
  previous_.reset();
  views_.clear();
  path_rivals_.clear();
  path_rivals_travel_ = -1;
  claim_test_ = ClaimTest{};
}

bool Localizer::take_kidnap_flag()
{
  const bool f = kidnap_flag_;
  kidnap_flag_ = false;
  return f;
}

std::vector<GatewayPassed> Localizer::take_gateway_events()
{
  std::vector<GatewayPassed> out;
  out.swap(passed_);
  return out;
}

bool Localizer::update(const sensors::LaserScan& scan, const Pose2& odom_from_base)
{
  ++stats_.scans;
  utime_ = scan.utime;
  scan_id_ = scan.scan_id;
  if (maps_.empty()) {
    mode_ = Mode::kNoMap;
    return false;
  }
  const auto points = beam_end_points(scan, options_.base_from_laser, options_.scan.beams, options_.scan.min_range);
  if (points.size() < kMinPoints) return false;

  if (mode_ == Mode::kTracking && kidnapped(points, odom_from_base)) {
    ++stats_.kidnaps;
    kidnap_flag_ = true;
    start_global();
  }
  if (mode_ == Mode::kUnknown) {
    particles_.clear();
    seed_global(points, static_cast<size_t>(options_.global.particles), &particles_);
    for (auto& p : particles_) p.weight = 1.0 / static_cast<double>(particles_.size());
    mode_ = Mode::kGlobal;
    global_travel_ = 0;
    odom_at_update_ = odom_from_base;
    views_.clear();
    views_.add(odom_from_base, coarse_points(points, options_.global.beams));
    weigh_estimate_resample(points);
    return true;
  }
  if (!odom_at_update_) {
    // A pose was just given: weigh the particles where they are.
    odom_at_update_ = odom_from_base;
    weigh_estimate_resample(points);
    return true;
  }
  const Pose2 delta = odom_at_update_->between(odom_from_base);
  if (delta.translation().norm() < options_.update_distance && std::fabs(delta.theta()) < options_.update_angle_deg * kDeg)
    return false;
  move_particles(delta);
  odom_at_update_ = odom_from_base;
  if (mode_ == Mode::kGlobal) {
    for (auto& h : path_rivals_) h.region_from_base = h.region_from_base * delta;
    global_travel_ += delta.translation().norm() + kTurnAsTravel * std::fabs(delta.theta());
    views_.add(odom_from_base, coarse_points(points, options_.global.beams));
  }
  weigh_estimate_resample(points);

  if (resuming_) {
    ++updates_since_pose_given_;
    if (estimate_.converged) {
      resuming_ = false;
    } else if (updates_since_pose_given_ >= options_.resume_give_up_updates) {
      start_global();   // the saved pose did not hold: search everywhere with the next scan
    }
  }
  return true;
}

void Localizer::weigh_estimate_resample(const std::vector<Vector2d>& points)
{
  const bool was_tracking = mode_ == Mode::kTracking;
  std::optional<Hypothesis> elsewhere;   // a place the path singles out that the cloud's mode is not
  double w_avg = 0;
  const auto weights = weigh(points, &w_avg);
  estimate_from(weights, points);
  // From an unknown pose, one place that fits is not yet the place: it must keep fitting while
  // the robot moves (the look-alike offices of a hallway fit one scan equally well).
  if (mode_ == Mode::kGlobal) {
    unsure_ = !estimate_.converged                          ? Unsure::kNotConverged
              : global_travel_ < options_.global.min_travel ? Unsure::kShortTravel
                                                            : claim_check(&elsewhere);
    if (unsure_ == Unsure::kNone) {
      mode_ = Mode::kTracking;
      views_.clear();
    }
  }
  if (mode_ == Mode::kTracking && estimate_.inlier_ratio < options_.recovery.kidnap_inlier_ratio) reassociate(points);
  // A jump while tracking: recovery particles from a search on one scan took over, at a place
  // nothing has yet told apart from its look-alikes. Like any kidnap, it is localized globally
  // anew (from the next scan), and claimed only once the views of the path single it out.
  if (was_tracking && jumped()) {
    ++stats_.kidnaps;
    kidnap_flag_ = true;
    start_global();
    ++stats_.updates;
    return;
  }
  if (mode_ == Mode::kTracking) track_region_change();
  previous_ = estimate_;
  resample(weights, points, w_avg);
  if (elsewhere) inject_at(*elsewhere);
  ++stats_.updates;
}

bool Localizer::kidnapped(const std::vector<Vector2d>& points, const Pose2& odom_from_base)
{
  if (!estimate_.valid || !odom_at_update_) return false;
  const RegionModel* m = maps_.region(estimate_.region);
  if (!m) return false;
  // The estimate carried forward by odometry since the last update.
  const Pose2 pose = estimate_.region_from_base * odom_at_update_->between(odom_from_base);
  // Explained by this region's map or by a neighbour's (near a gateway the robot may stand in
  // the part of a room its neighbour mapped better).
  double ratio = BeamScorer::inlier_ratio(m->field, pose, points, options_.scan.inlier_distance);
  for (const auto& l : m->links)
    if (const RegionModel* n = maps_.region(l.to))
      ratio = std::max(ratio, BeamScorer::inlier_ratio(n->field, l.here_from_there.inverse() * pose, points, options_.scan.inlier_distance));
  // The usual share at this kind of place: where the map is poor (a sparse line map, an open
  // area) the share is low all along, which is no kidnap; a kidnap makes it fall.
  const auto& rec = options_.recovery;
  inlier_usual_ = inlier_usual_ < 0 ? ratio : inlier_usual_ + rec.usual_alpha * (ratio - inlier_usual_);
  if (ratio >= rec.kidnap_inlier_ratio || ratio >= rec.kidnap_drop * inlier_usual_) {
    low_inlier_since_ = 0;
    return false;
  }
  if (low_inlier_since_ == 0) low_inlier_since_ = utime_;
  return static_cast<double>(utime_ - low_inlier_since_) * 1e-6 >= rec.kidnap_after_s;
}

std::vector<Hypothesis> Localizer::path_places(int64_t region, const Pose2& region_from_base,
                                               const std::vector<Hypothesis>& path_rivals) const
{
  // The pose and the best distinct places of the newest search elsewhere, all scored on the
  // views of the path: a look-alike that explains them about as well means the robot has not
  // yet seen what tells the places apart. (One scan is not enough: the offices along a hallway
  // look alike from their doors; the path past them differs.)
  std::vector<Hypothesis> out;
  if (!maps_.region(region) || views_.empty() || !odom_at_update_) return out;
  const auto& g = options_.global;
  const BeamScorer coarse(g.sigma, options_.scan.z_hit, options_.scan.z_rand, options_.scan.max_distance);
  const auto views = views_.placed(*odom_at_update_);
  // Every view scored in the region that holds the place it was taken from (path_score.h).
  const auto score_in = [&](int64_t r) {
    return [&, r](const Pose2& p) { return path_score(maps_, coarse, r, p, views, options_.handover_bbox_margin); };
  };
  // Every candidate refined as precisely as the pose, which is refined too: a twin place must
  // not lose only because the search grid missed it by a few centimetres, nor the pose because
  // odometry drift bent the path a little.
  const double step_xy = 0.5 * g.cell, step_theta = M_PI / g.headings;
  out.push_back(refine({region, region_from_base, 0}, score_in(region), step_xy, step_theta));
  // Distinct places only: the search keeps one candidate per freespace cell, so the best few
  // are often neighbouring cells of one look-alike place.
  std::vector<Hypothesis> taken{{region, region_from_base, 0}};
  // Refined; false if it climbed back onto the pose (then it is the pose itself, no rival).
  const auto add_rival = [&](const Hypothesis& h) {
    const Hypothesis rival = refine(h, score_in(h.region), step_xy, step_theta);
    if (same_place(taken.front(), rival)) return false;
    out.push_back(rival);
    return true;
  };
  const auto is_taken = [&](const Hypothesis& h) {
    return std::any_of(taken.begin(), taken.end(), [&](const Hypothesis& t) { return same_place(t, h); });
  };
  // The whole-path search's places (few, each a different place), then the newest scan
  // search's best `rivals` distinct places.
  for (const auto& h : path_rivals) {
    if (!maps_.region(h.region) || is_taken(h)) continue;
    taken.push_back(h);
    add_rival(h);
  }
  const size_t before = taken.size();
  for (const auto& h : last_search_) {
    if (!maps_.region(h.region) || is_taken(h)) continue;
    taken.push_back(h);
    if (!add_rival(h)) continue;
    if (static_cast<int>(taken.size() - before) >= g.rivals) break;
  }
  return out;
}

bool Localizer::same_place(const Hypothesis& a, const Hypothesis& b) const
{
  // A candidate nearby but turned by more than a few search steps is another place all the
  // same (a room that looks like itself turned round).
  const auto& g = options_.global;
  const RegionModel* ra = maps_.region(a.region);
  const RegionModel* rb = maps_.region(b.region);
  if (!ra || !rb) return false;
  const Pose2 pa = ra->map_from_region * a.region_from_base, pb = rb->map_from_region * b.region_from_base;
  return (pa.translation() - pb.translation()).norm() < g.unique_distance &&
         std::fabs(normalize_angle(pa.theta() - pb.theta())) < 3 * 2 * M_PI / g.headings;
}

double Localizer::path_margin(double views) const
{
  // Two places that fit equally well differ by a sum of per-view noise, whose spread grows with
  // the square root of the number of views: so does the margin, for the same risk per claim.
  return options_.global.unique_margin * std::sqrt(views);
}

Unsure Localizer::why_not_distinguishable(int64_t region, const Pose2& region_from_base, ClaimTest* test) const
{
  if (!maps_.region(region) || views_.empty() || !odom_at_update_) return Unsure::kShortTravel;
  if (last_search_.empty()) return Unsure::kNone;
  // Asked of any pose (the benchmark asks it of the truth): with a fresh search of the whole
  // path, not the one made for the estimate.
  const auto places = path_places(region, region_from_base, options_.global.claim_path_search ? search_path_rivals() : std::vector<Hypothesis>{});
  if (test) *test = lead_of(places, 0);
  // The path fits best somewhere else than the pose (hill climbing can wander off a wrong
  // pose towards a better place): the pose is not what the views say.
  const auto& eo = options_.estimate;
  const Pose2& refined = places.front().region_from_base;
  if ((refined.translation() - region_from_base.translation()).norm() > eo.converged_xy ||
      std::fabs(normalize_angle(refined.theta() - region_from_base.theta())) > eo.converged_theta_deg * kDeg)
    return Unsure::kPathElsewhere;
  const double margin = path_margin(static_cast<double>(views_.size()));
  for (size_t k = 1; k < places.size(); ++k)
    if (places[k].score > places.front().score - margin) return Unsure::kRival;
  return Unsure::kNone;
}

Unsure Localizer::claim_check(std::optional<Hypothesis>* elsewhere)
{
  // The estimate is claimed when it is distinguishable (above). When instead another place
  // explains the views of the path better than every other by the margin, the filter's cloud
  // has settled on a look-alike (a turned copy of the place, a neighbouring office) while the
  // path says where the robot is: that place is returned for recovery particles (inject_at),
  // and the filter, not the path alone, then decides.
  elsewhere->reset();
  if (!maps_.region(estimate_.region) || views_.empty() || !odom_at_update_) return Unsure::kShortTravel;
  if (last_search_.empty()) return Unsure::kNone;
  Unsure why = path_verdict(path_places(estimate_.region, estimate_.region_from_base, path_rivals_), elsewhere, &claim_test_);
  // Before a claim, every place of the map is asked (path_search.h), not only the scan search's
  // few hundred: at most once per view_spacing of travel (the places found are carried along
  // by odometry and refined on every update until the next search).
  const auto& g = options_.global;
  const bool searched_lately = path_rivals_travel_ >= 0 && global_travel_ - path_rivals_travel_ < g.view_spacing;
  if (why == Unsure::kNone && g.claim_path_search && !searched_lately) {
    path_rivals_ = search_path_rivals();
    path_rivals_travel_ = global_travel_;
    ++stats_.path_searches;
    why = path_verdict(path_places(estimate_.region, estimate_.region_from_base, path_rivals_), elsewhere, &claim_test_);
  }
  return why;
}

Unsure Localizer::path_verdict(const std::vector<Hypothesis>& places, std::optional<Hypothesis>* elsewhere, ClaimTest* test) const
{
  elsewhere->reset();
  *test = ClaimTest{};
  if (places.empty()) return Unsure::kShortTravel;
  size_t best = 0;
  for (size_t k = 1; k < places.size(); ++k)
    if (places[k].score > places[best].score) best = k;
  *test = lead_of(places, best);
  const bool clear = test->lead >= test->margin;
  const auto& eo = options_.estimate;
  const Pose2& e = estimate_.region_from_base;
  const Pose2& b = places[best].region_from_base;
  const bool at_estimate = places[best].region == estimate_.region && (b.translation() - e.translation()).norm() <= eo.converged_xy &&
                           std::fabs(normalize_angle(b.theta() - e.theta())) <= eo.converged_theta_deg * kDeg;
  test->best_is_estimate = best == 0 && at_estimate;
  if (clear && at_estimate) return Unsure::kNone;
  if (clear) *elsewhere = places[best];
  return best == 0 && at_estimate ? Unsure::kRival : Unsure::kPathElsewhere;
}

ClaimTest Localizer::lead_of(const std::vector<Hypothesis>& places, size_t c) const
{
  // With claim_judged_beams, the place must lead by the margin on the beams both maps can
  // judge (path_score.h BeamFit): a turned copy of the place whose map happens to hold a wall
  // the true place's map missed must not win on that gap.
  const auto& g = options_.global;
  ClaimTest t;
  t.places = static_cast<int>(places.size());
  t.views = static_cast<int>(views_.size());
  t.margin = path_margin(t.views);
  t.lead = 1e300;
  const auto views = views_.placed(*odom_at_update_);
  for (const auto& v : views) t.beams += static_cast<int>(v.points->size());
  const BeamScorer coarse(g.sigma, options_.scan.z_hit, options_.scan.z_rand, options_.scan.max_distance);
  const auto fits_of = [&](const Hypothesis& h) {
    return path_beam_fits(maps_, coarse, h.region, h.region_from_base, views, options_.handover_bbox_margin, g.sigma,
                          g.judged_through_gateways);
  };
  const auto own = g.claim_judged_beams ? fits_of(places[c]) : std::vector<BeamFit>{};
  for (size_t k = 0; k < places.size(); ++k) {
    if (k == c || same_place(places[k], places[c])) continue;
    const double all = places[c].score - places[k].score;
    const JudgedDifference judged = g.claim_judged_beams ? jointly_judged(own, fits_of(places[k])) : JudgedDifference{all, t.beams};
    if (judged.log_ratio >= t.lead) continue;
    t.lead = judged.log_ratio;
    t.lead_all_beams = all;
    t.judged_beams = judged.beams;
    const RegionModel* rc = maps_.region(places[c].region);
    const RegionModel* rk = maps_.region(places[k].region);
    if (rc && rk) {
      const Pose2 pc = rc->map_from_region * places[c].region_from_base, pk = rk->map_from_region * places[k].region_from_base;
      t.rival_distance = (pc.translation() - pk.translation()).norm();
      t.rival_turn_deg = normalize_angle(pk.theta() - pc.theta()) / kDeg;
    }
    // A rival within the margin decides the test: the rest are not scored (each is a walk of
    // every beam of the path), so the lead given is then that rival's, not always the weakest.
    if (t.lead < t.margin) break;
  }
  return t;
}

std::vector<Hypothesis> Localizer::search_path_rivals() const
{
  if (views_.empty() || !odom_at_update_) return {};
  const auto& g = options_.global;
  const BeamScorer coarse(g.sigma, options_.scan.z_hit, options_.scan.z_rand, options_.scan.max_distance);
  PathSearchOptions ps;
  ps.headings = 2 * g.headings;   // the far end of a path of metres feels half a scan-search step
  ps.beams_per_view = g.beams;
  ps.keep = g.path_search_places;
  return path_search(maps_, views_.placed(*odom_at_update_), coarse, ps,
                     [this](const Hypothesis& a, const Hypothesis& b) { return !same_place(a, b); }, progress_);
}

void Localizer::seed_global(const std::vector<Vector2d>& points, size_t count, std::vector<Particle>* out)
{
  ++stats_.global_searches;
  // While unsure, candidates are ranked by the views of the path (global_search.h).
  const bool path = mode_ == Mode::kGlobal && views_.size() >= 2 && odom_at_update_;
  const auto hyps = global_search(maps_, points, options_.global, options_.scan,
                                  path ? views_.placed(*odom_at_update_) : std::vector<PlacedView>{}, options_.handover_bbox_margin);
  last_search_ = hyps;
  if (hyps.empty()) return;
  // Equal shares: the coarse search ranks places roughly; the filter tells them apart as the
  // robot moves, so the true place must not be starved by a slightly better look-alike.
  std::normal_distribution<double> n01(0.0, 1.0);
  const double sxy = options_.global.seed_xy, sth = options_.global.seed_theta_deg * kDeg;
  for (size_t k = 0; k < count; ++k) {
    const auto& h = hyps[k % hyps.size()];
    Particle p;
    p.region = h.region;
    p.pose = Pose2(h.region_from_base.x() + sxy * n01(rng_), h.region_from_base.y() + sxy * n01(rng_),
                   h.region_from_base.theta() + sth * n01(rng_));
    out->push_back(p);
  }
}

void Localizer::move_particles(const Pose2& delta)
{
  for (auto& p : particles_) {
    p.pose = p.pose * sample_motion(delta, options_.motion, rng_);
    hand_over(&p);
  }
}

void Localizer::hand_over(Particle* p)
{
  // A particle leaves its region where the region ends: off its freespace, or beyond the
  // rectangle of its in-region measurements (a region's freespace may reach through an opening
  // into the next room, its rectangle does not); near one of its gateways it goes to the
  // neighbour beyond, if the neighbour holds the place (diss. 5.3).
  const RegionModel* m = maps_.region(p->region);
  const Vector2d here = p->pose.translation();
  if (!m || (m->is_free(here) && m->in_bbox(here, options_.handover_bbox_margin))) return;
  for (const auto& link : m->links) {
    double d = 1e300;
    for (const auto& [a, b] : link.lines) d = std::min(d, geometry::point_segment_distance(here, a, b));
    if (d > options_.handover_reach) continue;
    const Pose2 there = link.here_from_there.inverse() * p->pose;
    const RegionModel* n = maps_.region(link.to);
    if (!n || !n->is_free(there.translation()) || !n->in_bbox(there.translation(), options_.handover_bbox_margin)) continue;
    p->region = link.to;
    p->pose = there;
    ++stats_.particle_handovers;
    return;
  }
}

std::vector<double> Localizer::weigh(const std::vector<Vector2d>& points, double* mean_beam_likelihood)
{
  std::vector<double> logw(particles_.size());
  const double n = static_cast<double>(points.size());
  // Unsure of the place, one scan must not decide between look-alikes: a softer weight.
  const double beam_weight = mode_ == Mode::kGlobal ? options_.global.beam_weight : options_.scan.beam_weight;
  double best = -1e300, sum_beam = 0;
  for (size_t i = 0; i < particles_.size(); ++i) {
    const RegionModel* m = maps_.region(particles_[i].region);
    const double s = m ? scorer_.score(m->field, particles_[i].pose, points) : n * scorer_.floor();
    sum_beam += std::exp(s / n);
    logw[i] = std::log(std::max(particles_[i].weight, 1e-300)) + beam_weight * s;
    best = std::max(best, logw[i]);
  }
  *mean_beam_likelihood = particles_.empty() ? 0 : sum_beam / static_cast<double>(particles_.size());
  double total = 0;
  for (auto& w : logw) total += (w = std::exp(w - best));
  for (size_t i = 0; i < logw.size(); ++i) particles_[i].weight = (logw[i] /= total);
  return logw;
}

const RegionLink* Localizer::link_between(int64_t here, int64_t there) const
{
  const RegionModel* m = maps_.region(here);
  if (!m) return nullptr;
  for (const auto& l : m->links)
    if (l.to == there) return &l;
  return nullptr;
}

std::optional<Pose2> Localizer::in_frame_of(int64_t region, const Particle& p) const
{
  if (p.region == region) return p.pose;
  if (const RegionLink* l = link_between(region, p.region)) return l->here_from_there * p.pose;
  return std::nullopt;
}

void Localizer::estimate_from(const std::vector<double>& weights, const std::vector<Vector2d>& points)
{
  if (particles_.empty()) return;
  const auto& eo = options_.estimate;
  // The mode: the heaviest particle of the heaviest cell (region, cluster_xy, cluster_theta).
  // A lone particle of high weight (a recovery candidate) does not outweigh the cloud.
  std::unordered_map<uint64_t, double> cell_weight;
  const auto cell_of = [&](const Particle& p) {
    ParticleCount cells = options_.count;
    cells.bin_xy = eo.cluster_xy;
    cells.bin_theta_deg = eo.cluster_theta_deg;
    return bin_key(p, cells);
  };
  for (size_t i = 0; i < particles_.size(); ++i) cell_weight[cell_of(particles_[i])] += weights[i];
  uint64_t heaviest = 0;
  double heaviest_w = -1;
  for (const auto& [key, w] : cell_weight)
    if (w > heaviest_w) {
      heaviest_w = w;
      heaviest = key;
    }
  size_t best = 0;
  double best_w = -1;
  for (size_t i = 0; i < particles_.size(); ++i)
    if (weights[i] > best_w && cell_of(particles_[i]) == heaviest) {
      best_w = weights[i];
      best = i;
    }
  const int64_t r0 = particles_[best].region;
  const Pose2 mode = particles_[best].pose;
  // The cluster around the best particle, neighbouring regions' particles seen in r0's frame.
  std::vector<std::pair<Pose2, double>> cluster;
  std::map<int64_t, double> region_weight;
  double sw = 0, sx = 0, sy = 0, sc = 0, ss = 0;
  for (size_t i = 0; i < particles_.size(); ++i) {
    const auto q = in_frame_of(r0, particles_[i]);
    if (!q) continue;
    if ((q->translation() - mode.translation()).norm() > eo.cluster_xy ||
        std::fabs(normalize_angle(q->theta() - mode.theta())) > eo.cluster_theta_deg * kDeg)
      continue;
    const double w = weights[i];
    cluster.emplace_back(*q, w);
    region_weight[particles_[i].region] += w;
    sw += w;
    sx += w * q->x();
    sy += w * q->y();
    sc += w * std::cos(q->theta());
    ss += w * std::sin(q->theta());
  }
  Pose2 mean(sx / sw, sy / sw, std::atan2(ss, sc));
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& [q, w] : cluster) {
    const Eigen::Vector3d e(q.x() - mean.x(), q.y() - mean.y(), normalize_angle(q.theta() - mean.theta()));
    cov += (w / sw) * e * e.transpose();
  }
  // Reported in the region holding most of the cluster.
  int64_t region = r0;
  double most = 0;
  for (const auto& [r, w] : region_weight)
    if (w > most) {
      most = w;
      region = r;
    }
  if (region != r0) {
    const RegionLink* l = link_between(region, r0);
    mean = l->here_from_there * mean;
    Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();
    rot.topLeftCorner<2, 2>() = l->here_from_there.rotation();
    cov = rot * cov * rot.transpose();
  }
  const RegionModel* m = maps_.region(region);
  estimate_.valid = true;
  estimate_.utime = utime_;
  estimate_.scan_id = scan_id_;
  if (odom_at_update_) estimate_.odom_from_base = *odom_at_update_;
  estimate_.region = region;
  estimate_.region_from_base = mean;
  estimate_.map_from_base = m->map_from_region * mean;
  estimate_.covariance = cov;
  estimate_.cluster_share = sw;
  estimate_.inlier_ratio = BeamScorer::inlier_ratio(m->field, mean, points, options_.scan.inlier_distance);
  estimate_.converged = sw >= eo.min_cluster_share && std::sqrt(cov(0, 0) + cov(1, 1)) < eo.converged_xy &&
                        std::sqrt(cov(2, 2)) < eo.converged_theta_deg * kDeg;
  estimate_.confidence = estimate_.converged ? sw * estimate_.inlier_ratio : 0.0;
}

void Localizer::reassociate(const std::vector<Vector2d>& points)
{
  // A place can lie in several regions that share no gateway (one place mapped twice, before
  // the kernel merged them): when the estimate's region describes the view poorly, a region
  // that holds the same map-frame pose and describes it clearly better takes the cloud over.
  const RegionModel* own = maps_.region(estimate_.region);
  if (!own) return;
  const RegionModel* best = nullptr;
  double best_ratio = kReassociateGain * estimate_.inlier_ratio;
  for (const auto& [id, r] : maps_.regions()) {
    if (id == estimate_.region) continue;
    const Pose2 pose = r->map_from_region.inverse() * estimate_.map_from_base;
    if (!r->is_free(pose.translation()) || !r->in_bbox(pose.translation(), 0.0)) continue;
    const double ratio = BeamScorer::inlier_ratio(r->field, pose, points, options_.scan.inlier_distance);
    if (ratio > best_ratio && ratio >= options_.recovery.kidnap_inlier_ratio) {
      best_ratio = ratio;
      best = r.get();
    }
  }
  if (!best) return;
  // Every particle of the estimate's region moves through the map frame.
  const Pose2 best_from_own = best->map_from_region.inverse() * own->map_from_region;
  for (auto& p : particles_)
    if (p.region == estimate_.region) {
      p.region = best->id;
      p.pose = best_from_own * p.pose;
    }
  ++stats_.reassociations;
  estimate_.region_from_base = best_from_own * estimate_.region_from_base;
  estimate_.region = best->id;
  estimate_.inlier_ratio = best_ratio;
}

void Localizer::inject_at(const Hypothesis& place)
{
  // Half the cloud (its lightest particles) around the place: enough that the next scans can
  // confirm it against the cloud's mode, not so much that the path alone decides.
  constexpr double kShare = 0.5;
  const size_t n = static_cast<size_t>(std::lround(kShare * static_cast<double>(particles_.size())));
  if (n == 0) return;
  std::vector<size_t> order(particles_.size());
  std::iota(order.begin(), order.end(), 0);
  std::nth_element(order.begin(), order.begin() + static_cast<long>(n), order.end(),
                   [&](size_t a, size_t b) { return particles_[a].weight < particles_[b].weight; });
  const auto& g = options_.global;
  const double sxy = g.seed_xy, sth = g.seed_theta_deg * kDeg;
  std::normal_distribution<double> n01(0.0, 1.0);
  const double w = 1.0 / static_cast<double>(particles_.size());
  for (size_t k = 0; k < n; ++k) {
    Particle& p = particles_[order[k]];
    p.region = place.region;
    p.weight = w;
    p.pose = Pose2(place.region_from_base.x() + sxy * n01(rng_), place.region_from_base.y() + sxy * n01(rng_),
                   place.region_from_base.theta() + sth * n01(rng_));
  }
  double total = 0;
  for (const auto& p : particles_) total += p.weight;
  for (auto& p : particles_) p.weight /= total;
  stats_.recovery_particles += static_cast<int64_t>(n);
}

bool Localizer::jumped() const
{
  // Recovery particles that take over move the estimate farther than the robot drove: the robot
  // was somewhere else than the filter thought (a kidnap the inlier test did not catch).
  if (!previous_ || !previous_->valid || !previous_->converged || !estimate_.valid) return false;
  const RegionModel* was = maps_.region(previous_->region);
  const RegionModel* now = maps_.region(estimate_.region);
  if (!was || !now) return false;
  const Pose2 expected = was->map_from_region * previous_->region_from_base * previous_->odom_from_base.between(estimate_.odom_from_base);
  return (estimate_.map_from_base.translation() - expected.translation()).norm() >= options_.recovery.kidnap_jump;
}

void Localizer::track_region_change()
{
  if (!estimate_.valid) return;
  const int64_t now = estimate_.region;
  if (last_region_ != 0 && now != last_region_) {
    ++stats_.handovers;
    if (const RegionLink* l = link_between(last_region_, now)) {
      if (pending_pass_ && pending_pass_->to == last_region_ && pending_pass_->from == now) {
        pending_pass_.reset();   // went back before it was far enough past the gateway
      } else {
        pending_pass_ = PendingPass{l->gateway, last_region_, now};
      }
    }
  }
  last_region_ = now;
  if (!pending_pass_ || pending_pass_->to != now) return;
  const RegionModel* m = maps_.region(now);
  double d = 1e300;
  for (const auto& l : m->links)
    if (l.gateway == pending_pass_->gateway)
      for (const auto& [a, b] : l.lines) d = std::min(d, geometry::point_segment_distance(estimate_.region_from_base.translation(), a, b));
  if (d < options_.gateway_passed_distance || d > 1e299) return;
  passed_.push_back({utime_, pending_pass_->gateway, pending_pass_->from, now, estimate_.region_from_base, d});
  pending_pass_.reset();
}

void Localizer::replace_lightest(const std::vector<Vector2d>& points, double share)
{
  const size_t n = std::min(particles_.size(), static_cast<size_t>(std::lround(share * static_cast<double>(particles_.size()))));
  if (n == 0) return;
  std::vector<size_t> order(particles_.size());
  std::iota(order.begin(), order.end(), 0);
  std::nth_element(order.begin(), order.begin() + static_cast<long>(n), order.end(),
                   [&](size_t a, size_t b) { return particles_[a].weight < particles_[b].weight; });
  std::vector<Particle> fresh;
  seed_global(points, n, &fresh);
  const double w = 1.0 / static_cast<double>(particles_.size());
  for (size_t k = 0; k < fresh.size(); ++k) {
    fresh[k].weight = w;
    particles_[order[k]] = fresh[k];
  }
  double total = 0;
  for (const auto& p : particles_) total += p.weight;
  for (auto& p : particles_) p.weight /= total;
  stats_.recovery_particles += static_cast<int64_t>(fresh.size());
}

void Localizer::resample(const std::vector<double>& weights, const std::vector<Vector2d>& points, double w_avg)
{
  // Below this share the likelihood merely wobbles (people passing): no recovery.
  constexpr double kMinRecoveryShare = 0.05;
  auto& rec = options_.recovery;
  if (stats_.w_slow <= 0) {
    stats_.w_slow = stats_.w_fast = w_avg;
  } else {
    stats_.w_slow += rec.alpha_slow * (w_avg - stats_.w_slow);
    stats_.w_fast += rec.alpha_fast * (w_avg - stats_.w_fast);
  }
  // Augmented MCL's recovery share, but while tracking only when the estimate does not explain
  // the scan either: a likelihood dip alone (a turn, people) does not justify injecting
  // look-alike places, which a stacked map can make score well for an update or two.
  double recovery = std::clamp(1.0 - stats_.w_fast / stats_.w_slow, 0.0, rec.max_share);
  // While tracking, recovery only after the estimate has failed to explain the scans (as for a
  // kidnap: fewer inliers than usual) for half the kidnap time: a person in front of the laser
  // or a turn makes the likelihood dip, and look-alike places injected then could take over.
  const bool unexplained = low_inlier_since_ != 0 && static_cast<double>(utime_ - low_inlier_since_) * 1e-6 >= 0.5 * rec.kidnap_after_s;
  if (mode_ == Mode::kTracking && !unexplained) recovery = 0;
  if (mode_ == Mode::kGlobal) recovery = std::max(recovery, options_.global.reseed_share);

  // Resampling only when the weights have become uneven (effective sample size below half the
  // set, Doucet et al.): each resampling loses diversity, which global localization needs.
  double sum_sq = 0;
  for (double w : weights) sum_sq += w * w;
  const double ess = sum_sq > 0 ? 1.0 / sum_sq : 0.0;
  const bool uneven = ess < options_.count.resample_ess_ratio * static_cast<double>(weights.size());
  if (!uneven) {
    if (recovery >= kMinRecoveryShare) replace_lightest(points, recovery);
    stats_.particles = static_cast<int>(particles_.size());
    return;
  }

  // KLD: draw until the sample covers enough bins for its size.
  std::vector<double> cumulative(weights.size());
  std::partial_sum(weights.begin(), weights.end(), cumulative.begin());
  std::uniform_real_distribution<double> u01(0.0, cumulative.back());
  std::unordered_set<uint64_t> bins;
  int n = 0;
  const int cap = mode_ == Mode::kGlobal ? std::max(options_.count.max, options_.global.particles) : options_.count.max;
  while (n < cap) {
    const size_t i = static_cast<size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), u01(rng_)) - cumulative.begin());
    bins.insert(bin_key(particles_[std::min(i, particles_.size() - 1)], options_.count));
    ++n;
    if (n >= options_.count.min && n >= kld_sample_count(static_cast<int>(bins.size()), options_.count)) break;
  }
  const size_t n_recovery = recovery >= kMinRecoveryShare ? static_cast<size_t>(std::lround(n * recovery)) : 0;
  std::vector<Particle> next;
  next.reserve(static_cast<size_t>(n));
  for (size_t i : low_variance_resample(weights, static_cast<size_t>(n) - n_recovery, rng_)) next.push_back(particles_[i]);
  if (n_recovery > 0) {
    seed_global(points, n_recovery, &next);
    stats_.recovery_particles += static_cast<int64_t>(n_recovery);
  }
  for (auto& p : next) p.weight = 1.0 / static_cast<double>(next.size());
  particles_ = std::move(next);
  stats_.particles = static_cast<int>(particles_.size());
}

}  // namespace rgnav::localizer
