#include "scan_mapper/scan_mapper.h"

#include "scan_mapper/input_checks.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rgnav::scan_mapper {
namespace {

constexpr size_t kSubmapCacheSize = 24;

// [rad^2] The heading variance of a fit that kept odometry's heading (one radian: no measurement).
constexpr double kUnmeasuredHeadingVariance = 1.0;

// Rotation acting on the (x, y) part of a pose covariance.
Eigen::Matrix3d rot3(double th)
{
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  R(0, 0) = std::cos(th);
  R(0, 1) = -std::sin(th);
  R(1, 0) = std::sin(th);
  R(1, 1) = std::cos(th);
  return R;
}

Eigen::Matrix3d information_of(const Eigen::Matrix3d& cov)
{
  Eigen::Matrix3d c = 0.5 * (cov + cov.transpose());
  c.diagonal() += Eigen::Vector3d(1e-8, 1e-8, 1e-10);
  Eigen::Matrix3d info = c.inverse();
  return 0.5 * (info + info.transpose());
}

Eigen::Vector3d difference(const Pose2& a, const Pose2& b)
{
  return {a.x() - b.x(), a.y() - b.y(), normalize_angle(a.theta() - b.theta())};
}

}  // namespace

ScanMapper::ScanMapper(ScanMapperOptions options)
    : options_(std::move(options)), odometry_scale_(options_.odometry_scale)
{
}

ScanMapper::ScanMapper(ScanMapperOptions options, MapperState state)
    : options_(std::move(options)), nodes_(std::move(state.nodes)), odometry_scale_(options_.odometry_scale)
{
  for (auto& n : nodes_) {
    if (n.normals.size() != n.points.size()) compute_normals(&n);
    graph_.add_node(n.map_from_base);
  }
  for (const auto& e : state.edges)
    if (e.from >= 0 && e.to >= 0 && e.from < static_cast<int>(nodes_.size()) && e.to < static_cast<int>(nodes_.size()))
      graph_.add_edge(e);
  relocalize_next_ = !nodes_.empty();
}

MapperState ScanMapper::state() const { return {nodes_, graph_.edges()}; }

void ScanMapper::add_odometry(const OdometrySample& s)
{
  if (!check_odometry(s).empty()) {
    ++stats_.invalid;
    return;
  }
  odometry_.add(s);
}

void ScanMapper::reset_odometry()
{
  odometry_.clear();
  relocalize_next_ = !nodes_.empty();
}

std::optional<Pose2> ScanMapper::current_pose() const
{
  if (nodes_.empty()) return std::nullopt;
  return nodes_.back().map_from_base;
}

std::optional<Pose2> ScanMapper::map_from_odom() const
{
  if (nodes_.empty() || relocalize_next_) return std::nullopt;
  return nodes_.back().map_from_base * nodes_.back().odom_from_base.inverse();
}

MapperUpdate ScanMapper::add_scan(const sensors::LaserScan& scan)
{
  ++stats_.scans_in;
  if (!check_scan(scan).empty()) {
    ++stats_.invalid;
    return {};
  }
  const auto odom = odometry_.at(scan.utime, options_.max_odometry_extrapolation_us);
  if (!odom) {
    ++stats_.no_odometry;
    return {};
  }
  return process(scan, *odom);
}

Eigen::Matrix3d ScanMapper::odometry_covariance(const Pose2& inc, double trans_scale) const
{
  const auto& n = options_.odometry_noise;
  const double d = translation_norm(inc);
  const double st = trans_scale * (n.min_trans_m + n.trans_per_m * d);
  const double sr = n.min_rot_rad + n.rot_per_rad * std::fabs(inc.theta()) + n.rot_per_m * d;
  return Eigen::Vector3d(st * st, st * st, sr * sr).asDiagonal();
}

void ScanMapper::learn_odometry_noise(const Pose2& increment, const Eigen::Vector3d& innovation,
                                      const Eigen::Matrix3d& R)
{
  const auto& n = options_.odometry_noise;
  if (n.adapt_window_scans <= 0) return;
  const Eigen::Matrix2d S = odometry_covariance(increment, 1.0).topLeftCorner<2, 2>() + R.topLeftCorner<2, 2>();
  const Eigen::Vector2d e = innovation.head<2>();
  // Per axis; one wrong match counts as a 5-sigma one at most.
  const double k = std::min(0.5 * e.dot(S.ldlt().solve(e)), 25.0);
  ++innovation_samples_;
  innovation_ratio_ +=
      (k - innovation_ratio_) / static_cast<double>(std::min<int64_t>(innovation_samples_, n.adapt_window_scans));
  stats_.odometry_trans_scale = std::sqrt(std::clamp(innovation_ratio_, 1.0, n.adapt_max_scale * n.adapt_max_scale));
}

IcpOptions ScanMapper::fit_options() const
{
  IcpOptions o = options_.icp;
  if (options_.odometry_noise.adapt_degeneracy) {
    const double s = stats_.odometry_trans_scale;
    o.degenerate_min_points /= s * s;
  }
  return o;
}

MapperUpdate ScanMapper::process(const sensors::LaserScan& scan, const Pose2& odom)
{
  MapperUpdate up;
  ScanNode node;
  node.odom_from_base = odom;
  if (nodes_.empty()) {
    // The map frame is the odometry frame at the first scan.
    node.scan = scan;
    node.map_from_base = odom;
    node.published = odom;
    prepare_points(&node);
    nodes_.push_back(std::move(node));
    graph_.add_node(nodes_.back().map_from_base);
    ++stats_.accepted;
    up.accepted = true;
    up.node = 0;
    return up;
  }
  const ScanNode& prev = nodes_.back();
  const bool relocalize = relocalize_next_;
  // After a restart the odometry origin is unknown: assume the robot is where it was.
  const Pose2 raw = relocalize ? Pose2{} : between(prev.odom_from_base, odom);
  if (!relocalize && translation_norm(raw) < options_.min_travel_m && std::fabs(raw.theta()) < options_.min_rotation_rad)
    return up;
  relocalize_next_ = false;
  // Odometry's increment with its learned scale error taken out.
  const Pose2 u = odometry_scale_.corrected(raw);

  node.scan = scan;
  prepare_points(&node);
  const Eigen::Matrix3d Q = relocalize ? Eigen::Matrix3d(Eigen::Vector3d(1.0, 1.0, 0.5).asDiagonal())
                                       : odometry_covariance(u, stats_.odometry_trans_scale);
  const Pose2 guess = prev.map_from_base * u;
  const IcpOptions fit = fit_options();

  Pose2 fused = u;
  Eigen::Matrix3d P = Q;
  // The candidates best fit first; the first one odometry does not contradict is fused.
  bool rejected = false;
  for (const IcpResult& icp : register_locally(node, guess, relocalize, std::sqrt(Q(2, 2)), fit)) {
    // Both increments in the previous node's frame.
    const Pose2 z = between(prev.map_from_base, icp.map_from_scan);
    const Eigen::Matrix3d R = rot3(-prev.map_from_base.theta()) * icp.covariance * rot3(-prev.map_from_base.theta()).transpose();
    const Eigen::Vector3d innov = difference(z, u);
    const Eigen::Matrix3d S = Q + R;
    const double chi2 = innov.dot(S.ldlt().solve(innov));
    if (!relocalize && chi2 > options_.max_innovation_chi2) {
      rejected = true;
      continue;
    }
    const Eigen::Matrix3d K = Q * S.inverse();
    fused = pose_from_vector(to_vector(u) + K * innov);
    P = (Eigen::Matrix3d::Identity() - K) * Q;
    P = 0.5 * (P + P.transpose());
    if (icp.weakest_translation_points < fit.degenerate_min_points) ++stats_.axes_held;
    // Where the fit holds both translation directions, its difference from odometry measures
    // odometry's translation error. Held by the configured count, whatever the odometry: a fit
    // that the fusion trusts against a poor odometry with fewer points is still too weak to say
    // by how much that odometry errs.
    const double weak_limit = options_.icp.degenerate_min_points;
    if (!relocalize && (weak_limit <= 0.0 || icp.weakest_translation_points >= weak_limit)) {
      learn_odometry_noise(u, innov, R);
      odometry_scale_.add(raw, z);
      stats_.odometry_scale = odometry_scale_.scale();
    }
    up.matched = true;
    ++stats_.matched;
    break;
  }
  if (rejected && !up.matched) ++stats_.match_rejected;
  node.map_from_base = prev.map_from_base * fused;
  node.published = node.map_from_base;
  // First-order propagation of the node covariance.
  const Eigen::Vector2d dt = Eigen::Vector2d(node.map_from_base.x() - prev.map_from_base.x(),
                                             node.map_from_base.y() - prev.map_from_base.y());
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F(0, 2) = -dt.y();
  F(1, 2) = dt.x();
  const Eigen::Matrix3d G = rot3(prev.map_from_base.theta());
  node.covariance = F * prev.covariance * F.transpose() + G * P * G.transpose();
  node.path_m = prev.path_m + translation_norm(u);

  const int from = static_cast<int>(nodes_.size()) - 1;
  nodes_.push_back(std::move(node));
  const int id = graph_.add_node(nodes_.back().map_from_base);
  // The edge error lives in the frame of the measured increment.
  const Eigen::Matrix3d Pe = rot3(-fused.theta()) * P * rot3(-fused.theta()).transpose();
  graph_.add_edge({from, id, fused, information_of(Pe), false});
  ++stats_.accepted;
  up.accepted = true;
  up.node = id;
  // While a hypothesis waits for a witness, look every scan.
  if (options_.loop.enabled && !in_flight_ && (++since_loop_try_ >= options_.loop.every_n_scans || !pending_.empty())) {
    since_loop_try_ = 0;
    note_progress();
    up.loop_closed = try_loop_closure(id, &up);
  }
  return up;
}

void ScanMapper::prepare_points(ScanNode* node) const
{
  node->points = scan_to_points(node->scan, options_.base_from_laser, options_.points);
  compute_normals(node);
}

void ScanMapper::compute_normals(ScanNode* node) const
{
  auto normals = scan_normals(node->points, options_.base_from_laser.translation(), options_.normals);
  node->normals = std::move(normals.normals);
  node->has_normal = std::move(normals.has_normal);
}

std::vector<IcpResult> ScanMapper::register_locally(const ScanNode& scan, const Pose2& guess, bool wide,
                                                    double odometry_sigma_rot, const IcpOptions& icp)
{
  const Points& points = scan.points;
  const int n = static_cast<int>(nodes_.size());
  Points model, normals;
  std::vector<char> has_normal;
  for (int k = std::max(0, n - options_.local_map_scans); k < n; ++k) {
    const auto& nk = nodes_[static_cast<size_t>(k)];
    const auto pts = transform_points(nk.map_from_base, nk.points);
    model.insert(model.end(), pts.begin(), pts.end());
    const double c = std::cos(nk.map_from_base.theta()), s = std::sin(nk.map_from_base.theta());
    for (const auto& v : nk.normals) normals.emplace_back(c * v.x() - s * v.y(), s * v.x() + c * v.y());
    has_normal.insert(has_normal.end(), nk.has_normal.begin(), nk.has_normal.end());
  }
  if (model.size() < 10 || points.size() < 10) return {};
  const PointMap map(std::move(model), std::move(normals), std::move(has_normal));
  std::vector<IcpResult> found{icp_point_to_line(points, scan.normals, scan.has_normal, map, guess, icp)};
  note_progress();
  if (wide || !found[0].ok || found[0].inlier_ratio < options_.min_inlier_ratio) {
    ++stats_.correlative_retries;
    const LikelihoodGrid grid(map.points(), options_.correlative);
    CorrelativeWindow window = options_.local_window;
    if (wide) window = {options_.loop.window_max_m, options_.loop.angular_window_max_rad};
    const auto cor = correlative_match(thin_points(points, options_.loop.point_spacing_m), grid, guess, window,
                                       options_.correlative);
    note_progress();
    // A wide search can fit a turned copy of symmetric surroundings (a round bay seen from its
    // centre) better than the fit from odometry: both go to the caller, better first.
    IcpResult again = icp_point_to_line(points, scan.normals, scan.has_normal, map, cor.map_from_scan, icp);
    if (again.ok && (!found[0].ok || again.inlier_ratio > found[0].inlier_ratio)) found.insert(found.begin(), again);
    else found.push_back(again);
  }
  std::vector<IcpResult> accepted;
  std::optional<IcpResult> held;   // the translation-only fit at the guess's heading, if needed
  bool held_used = false;
  for (IcpResult& r : found) {
    if (!r.ok) continue;
    if (options_.moving_points.margin_m > 0.0)
      if (auto refit = register_without_moving(scan, map, r.map_from_scan, icp)) r = *refit;
    if (!r.ok || r.inlier_ratio < options_.min_accept_inlier_ratio) continue;
    // After a restart (wide) the guess's heading is no odometry's: nothing to check against.
    const double turn = normalize_angle(r.map_from_scan.theta() - guess.theta());
    const double max_turn = options_.turn_check_sigmas * odometry_sigma_rot;
    if (!wide && options_.turn_check_sigmas > 0.0 && std::fabs(turn) > max_turn) {
      // The fit at odometry's heading, once per scan however many candidates turned.
      if (!held) {
        IcpOptions translation_only = icp;
        translation_only.estimate_rotation = false;
        held = icp_point_to_line(points, scan.normals, scan.has_normal, map, guess, translation_only);
        // Its heading is odometry's, unmeasured by the fit.
        held->covariance.row(2).setZero();
        held->covariance.col(2).setZero();
        held->covariance(2, 2) = kUnmeasuredHeadingVariance;
        held->fit_covariance = held->covariance;
      }
      const bool few_gained = held->inlier_ratio + options_.turn_min_inlier_gain > r.inlier_ratio;
      const bool less_precise =
          options_.turn_max_rms_ratio > 0.0 && r.surface_rms_m > options_.turn_max_rms_ratio * held->surface_rms_m;
      if (held->ok && (few_gained || less_precise)) {
        // The scan does not hold the turn: the held fit stands in for it (once).
        if (!held_used) accepted.push_back(*held);
        held_used = true;
        continue;
      }
    }
    accepted.push_back(r);
  }
  if (held_used) ++stats_.turns_held;
  return accepted;
}

std::optional<IcpResult> ScanMapper::register_without_moving(const ScanNode& scan, const PointMap& map,
                                                             const Pose2& map_from_scan, const IcpOptions& icp)
{
  const auto& o = options_.moving_points;
  const int n = static_cast<int>(nodes_.size());
  const int first = std::max(0, n - options_.local_map_scans);
  // The local map's scans see through the new scan's points on something that has since come
  // (a person walking toward the laser) ...
  std::vector<ScanView> model_views;
  for (int k = first; k < n; ++k) {
    const auto& nk = nodes_[static_cast<size_t>(k)];
    model_views.emplace_back(nk.scan, nk.map_from_base * options_.base_from_laser, o);
  }
  const Points here = transform_points(map_from_scan, scan.points);
  const double c = std::cos(map_from_scan.theta()), s = std::sin(map_from_scan.theta());
  Points here_normals;
  here_normals.reserve(scan.normals.size());
  for (const auto& v : scan.normals) here_normals.emplace_back(c * v.x() - s * v.y(), s * v.x() + c * v.y());
  std::vector<char> keep_scan;
  mark_seen_through(model_views, here, here_normals, scan.has_normal, &keep_scan);
  // ... and the new scan sees through the local map's points on something that has gone (the
  // trail a person walking away leaves).
  const std::vector<ScanView> scan_view{ScanView(scan.scan, map_from_scan * options_.base_from_laser, o)};
  std::vector<char> keep_model;
  mark_seen_through(scan_view, map.points(), map.normals(), map.has_normals(), &keep_model);
  const auto moving = [](const std::vector<char>& keep) { return std::count(keep.begin(), keep.end(), 0); };
  const auto moved_scan = moving(keep_scan), moved_model = moving(keep_model);
  if (moved_scan == 0 && moved_model == 0) return std::nullopt;
  stats_.moving_points += moved_scan + moved_model;

  struct Kept
  {
    Points points, normals;
    std::vector<char> has_normal;
  };
  const auto kept = [](const std::vector<char>& keep, const Points& p, const Points& n, const std::vector<char>& h) {
    Kept k;
    for (size_t i = 0; i < keep.size(); ++i)
      if (keep[i]) {
        k.points.push_back(p[i]);
        k.normals.push_back(n[i]);
        k.has_normal.push_back(h[i]);
      }
    return k;
  };
  const Kept still_scan = kept(keep_scan, scan.points, scan.normals, scan.has_normal);
  Kept model = kept(keep_model, map.points(), map.normals(), map.has_normals());
  if (model.points.size() < 10 || still_scan.points.size() < 10) return std::nullopt;
  const PointMap still(std::move(model.points), std::move(model.normals), std::move(model.has_normal));
  IcpResult refit =
      icp_point_to_line(still_scan.points, still_scan.normals, still_scan.has_normal, still, map_from_scan, icp);
  if (!refit.ok) return std::nullopt;
  return refit;
}

const ScanMapper::Submap& ScanMapper::submap_around(int anchor)
{
  auto it = submaps_.find(anchor);
  if (it != submaps_.end()) {
    submap_lru_.remove(anchor);
    submap_lru_.push_front(anchor);
    return it->second;
  }
  const auto& l = options_.loop;
  const Pose2 anchor_from_map = nodes_[static_cast<size_t>(anchor)].map_from_base.inverse();
  const int last = static_cast<int>(nodes_.size()) - 1 - l.min_node_gap;
  Points pts, normals;
  std::vector<char> has_normal;
  const double r2 = l.submap_radius_m * l.submap_radius_m;
  for (int k = std::max(0, anchor - l.submap_half_nodes); k <= std::min(last, anchor + l.submap_half_nodes); ++k) {
    const auto& nk = nodes_[static_cast<size_t>(k)];
    const Pose2 anchor_from_node = anchor_from_map * nk.map_from_base;
    const double c = std::cos(anchor_from_node.theta()), s = std::sin(anchor_from_node.theta());
    for (size_t i = 0; i < nk.points.size(); ++i) {
      const Eigen::Vector2d p = anchor_from_node * nk.points[i];
      if (p.squaredNorm() > r2) continue;
      pts.push_back(p);
      // Each scan's own oriented normals: a normal from the merged points would mix the two
      // faces of a thin wall.
      const auto& v = nk.normals[i];
      normals.emplace_back(c * v.x() - s * v.y(), s * v.x() + c * v.y());
      has_normal.push_back(nk.has_normal[i]);
    }
  }
  Submap sm;
  sm.grid = std::make_unique<LikelihoodGrid>(pts, l.correlative);
  note_progress();
  sm.points = std::make_unique<PointMap>(std::move(pts), std::move(normals), std::move(has_normal));
  submap_lru_.push_front(anchor);
  if (submap_lru_.size() > kSubmapCacheSize) {
    submaps_.erase(submap_lru_.back());
    submap_lru_.pop_back();
  }
  return submaps_.emplace(anchor, std::move(sm)).first->second;
}

std::optional<ClosureHypothesis> ScanMapper::find_closure(int n)
{
  const auto& l = options_.loop;
  const ScanNode& cur = nodes_[static_cast<size_t>(n)];
  // How well each old node is known relative to this one, read off the graph.
  const auto unc = relative_uncertainty(graph_, n, l.drift);
  note_progress();
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (int m = 0; m + l.min_node_gap <= n; ++m) {
    const ScanNode& c = nodes_[static_cast<size_t>(m)];
    if (cur.path_m - c.path_m < l.min_path_gap_m) break;  // path_m grows with m
    const auto& u = unc[static_cast<size_t>(m)];
    if (!u.reached()) continue;
    const double window = std::clamp(l.gate_sigmas * u.sigma_xy(), l.window_base_m, l.window_max_m);
    const double d = std::hypot(c.map_from_base.x() - cur.map_from_base.x(), c.map_from_base.y() - cur.map_from_base.y());
    // Beyond the window the true place cannot be this one; prefer the best-known candidates.
    if (d > l.search_radius_m + window) continue;
    const double rank = d / (l.search_radius_m + window);
    if (rank < best_d) {
      best_d = rank;
      best = m;
    }
  }
  if (best < 0) return std::nullopt;
  ++stats_.loop_attempts;
  // Anchors on a coarse lattice so that nearby attempts share a cached submap.
  const int step = std::max(1, l.submap_half_nodes);
  int anchor = static_cast<int>(std::lround(static_cast<double>(best) / step)) * step;
  anchor = std::min(anchor, n - l.min_node_gap);
  const Submap& sm = submap_around(anchor);
  if (sm.points->size() < 20) return std::nullopt;
  const ScanNode& a = nodes_[static_cast<size_t>(anchor)];
  const auto& u = unc[static_cast<size_t>(anchor)];
  const double sxy = u.reached() ? u.sigma_xy() : l.window_max_m;
  const double sth = u.reached() ? u.sigma_rot() : l.angular_window_max_rad;
  const Pose2 guess = between(a.map_from_base, cur.map_from_base);
  const CorrelativeWindow window{std::clamp(l.gate_sigmas * sxy, l.window_base_m, l.window_max_m),
                                 std::clamp(l.gate_sigmas * sth, l.angular_window_base_rad, l.angular_window_max_rad)};
  const bool ambiguity_checked = l.max_ambiguity < 1.0;
  const auto cor = correlative_match(thin_points(cur.points, l.point_spacing_m), *sm.grid, guess, window, l.correlative,
                                     ambiguity_checked ? l.ambiguity_distance_m : 0.0);
  note_progress();
  if (cor.score < l.min_score) return std::nullopt;
  if (ambiguity_checked && cor.runner_up >= l.max_ambiguity * cor.score) {
    ++stats_.loop_ambiguous;
    return std::nullopt;
  }
  IcpOptions loop_icp = fit_options();
  loop_icp.degenerate_variance_m2 = l.degenerate_variance_m2;
  IcpResult icp = icp_point_to_line(cur.points, cur.normals, cur.has_normal, *sm.points, cor.map_from_scan, loop_icp);
  // The correlative optimum is only as good as its grid; where the graph already knows the
  // relative pose, ICP from there may find a better fit that the coarse search stepped over.
  const IcpResult from_guess = icp_point_to_line(cur.points, cur.normals, cur.has_normal, *sm.points, guess, loop_icp);
  if (from_guess.ok && (!icp.ok || from_guess.inlier_ratio > icp.inlier_ratio ||
                        (from_guess.inlier_ratio == icp.inlier_ratio && from_guess.rms_m < icp.rms_m)))
    icp = from_guess;
  // A fit whose surface residuals are well above the range noise explains the scan by the wrong
  // structure (a wall face seen from the other side, a look-alike doorway): its Hessian-based
  // covariance says nothing about how far off it is.
  if (!icp.ok || icp.inlier_ratio < l.min_inlier_ratio || icp.surface_rms_m > l.max_rms_m) return std::nullopt;
  ClosureHypothesis h;
  h.node = n;
  h.anchor = anchor;
  h.path_m = cur.path_m;
  h.anchor_from_node = icp.map_from_scan;
  h.covariance = l.covariance_scale * rot3(-h.anchor_from_node.theta()) * icp.covariance * rot3(-h.anchor_from_node.theta()).transpose();
  if (icp.weakest_translation_points < loop_icp.degenerate_min_points) {
    // The fit does not hold its weakest direction (a hallway's axis; scan_mapper_options.h).
    if (l.degenerate_keeps_graph_axis) {
      const Eigen::Vector2d& v = icp.weakest_direction;
      const Eigen::Vector2d t = icp.map_from_scan.translation() - v.dot(icp.map_from_scan.translation() - guess.translation()) * v;
      h.anchor_from_node = Pose2(t.x(), t.y(), icp.map_from_scan.theta());
    }
    h.covariance *= l.degenerate_covariance_scale;
  }
  // Where the graph already knows the relative pose well, a match that agrees with it needs
  // no second witness.
  h.direct = false;
  if (u.reached() && u.sigma_xy() <= l.direct_max_sigma_m) {
    const Eigen::Vector3d r = edge_error(graph_.pose(anchor), graph_.pose(n), h.anchor_from_node);
    // The fit's own precision, not the degeneracy terms: along a hallway those let a match slide
    // to the look-alike door 2-4 m on and still "agree" (a hallway of identical doors).
    Eigen::Matrix3d S = l.covariance_scale * rot3(-h.anchor_from_node.theta()) * icp.fit_covariance *
                        rot3(-h.anchor_from_node.theta()).transpose();
    S.diagonal() += Eigen::Vector3d(u.sigma_xy() * u.sigma_xy(), u.sigma_xy() * u.sigma_xy(), u.var_rot);
    h.direct = r.dot(S.ldlt().solve(r)) <= l.direct_max_chi2;
  }
  return h;
}

bool ScanMapper::try_loop_closure(int n, MapperUpdate* up)
{
  const auto& l = options_.loop;
  const auto h = find_closure(n);
  // Hypotheses that waited too long for a witness expire.
  pending_.erase(std::remove_if(pending_.begin(), pending_.end(),
                                [&](const ClosureHypothesis& p) { return n - p.node > l.confirm_within_nodes; }),
                 pending_.end());
  if (!h) return false;
  std::vector<ClosureHypothesis> accept;
  if (h->direct) {
    accept.push_back(*h);
  } else {
    for (const auto& p : pending_)
      if (p.node != h->node && witnesses(graph_, p, *h, l.consistency, l.witness_min_travel_m)) accept.push_back(p);
    if (accept.empty()) {
      pending_.push_back(*h);
      return false;
    }
    accept.push_back(*h);
    // The witnesses are used; the rest may still be confirmed later.
    pending_.erase(std::remove_if(pending_.begin(), pending_.end(),
                                  [&](const ClosureHypothesis& p) {
                                    return std::any_of(accept.begin(), accept.end(), [&](const ClosureHypothesis& q) {
                                      return q.node == p.node && q.anchor == p.anchor;
                                    });
                                  }),
                   pending_.end());
  }
  OptimizationJob job;
  job.graph = graph_;
  job.first_closure = graph_.edges().size();
  for (const auto& c : accept) job.graph.add_edge({c.anchor, c.node, c.anchor_from_node, information_of(c.covariance), true});
  job.newest = n;
  job.anchor = accept.back().anchor;
  job.closure_covariance = accept.back().covariance;
  job.options = options_.optimizer;
  job.max_residual_chi2 = l.max_residual_chi2;
  job.max_strain_chi2 = l.max_strain_chi2;
  job.prune_earlier = l.prune_earlier_closures;
  if (deferred_) {
    job_ = std::move(job);
    in_flight_ = true;
    up->optimization_ready = true;
    return false;
  }
  job.run();
  return adopt(job, up, n);
}

std::optional<OptimizationJob> ScanMapper::take_optimization_job()
{
  std::optional<OptimizationJob> j = std::move(job_);
  job_.reset();
  return j;
}

MapperUpdate ScanMapper::apply_optimization(const OptimizationJob& done)
{
  in_flight_ = false;
  MapperUpdate up;
  up.node = static_cast<int>(nodes_.size()) - 1;
  up.loop_closed = adopt(done, &up, -1);
  return up;
}

bool ScanMapper::adopt(const OptimizationJob& job, MapperUpdate* up, int unpublished)
{
  const PoseGraph& g = job.graph;
  // A batch the job judged false is dropped whole and the estimate stays as it was.
  if (job.verdict != OptimizationJob::Verdict::kHolds) {
    ++stats_.loop_rejected_after_opt;
    if (job.verdict == OptimizationJob::Verdict::kStrained) ++stats_.loop_rejected_strain;
    return false;
  }
  // Earlier closures the job took out (in deferred mode graph_ has gained sequential edges
  // since, never closures: only adopt() adds those).
  for (const auto& [from, to] : job.pruned)
    for (size_t k = graph_.edges().size(); k-- > 0;) {
      const auto& e = graph_.edges()[k];
      if (e.robust && e.from == from && e.to == to) {
        graph_.remove_edge(k);
        ++stats_.loop_pruned;
        break;
      }
    }
  for (size_t k = job.first_closure; k < g.edges().size(); ++k) graph_.add_edge(g.edges()[k]);
  // Nodes added while the job ran follow the newest node it knew, rigidly.
  const int known = static_cast<int>(g.size());
  const Pose2 old_last = graph_.pose(known - 1);
  const Pose2 correction = g.pose(known - 1) * old_last.inverse();
  for (int i = 0; i < known; ++i) graph_.set_pose(i, g.pose(i));
  for (int i = known; i < static_cast<int>(graph_.size()); ++i) graph_.set_pose(i, correction * graph_.pose(i));
  stats_.loop_closures += static_cast<int64_t>(g.edges().size() - job.first_closure);
  collect_corrections(up, unpublished);
  auto& last = nodes_[static_cast<size_t>(job.newest)];
  const ScanNode& a = nodes_[static_cast<size_t>(job.anchor)];
  last.covariance = a.covariance + rot3(a.map_from_base.theta()) * job.closure_covariance * rot3(a.map_from_base.theta()).transpose();
  // Relative poses inside cached submaps changed.
  submaps_.clear();
  submap_lru_.clear();
  return true;
}

void ScanMapper::collect_corrections(MapperUpdate* up, int unpublished)
{
  const int newest = static_cast<int>(nodes_.size()) - 1;
  for (int i = 0; i <= newest; ++i) {
    auto& node = nodes_[static_cast<size_t>(i)];
    const Pose2& now = graph_.pose(i);
    node.map_from_base = now;
    if (i == unpublished) {
      node.published = now;
      continue;
    }
    const Eigen::Vector3d d = difference(now, node.published);
    if (std::hypot(d.x(), d.y()) >= options_.republish_min_change_m || std::fabs(d.z()) >= options_.republish_min_change_rad) {
      ++node.revision;
      node.published = now;
      up->corrected.push_back(i);
    }
  }
}

}  // namespace rgnav::scan_mapper
