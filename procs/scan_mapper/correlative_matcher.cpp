#include "scan_mapper/correlative_matcher.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace rgnav::scan_mapper {

LikelihoodGrid::LikelihoodGrid(const Points& points, const CorrelativeOptions& o, double margin_m)
    : res_(o.resolution_m), b_(std::max(1, o.coarse_factor))
{
  if (points.empty()) return;
  double x1 = -std::numeric_limits<double>::infinity(), y1 = x1;
  x0_ = y0_ = std::numeric_limits<double>::infinity();
  for (const auto& p : points) {
    x0_ = std::min(x0_, p.x());
    y0_ = std::min(y0_, p.y());
    x1 = std::max(x1, p.x());
    y1 = std::max(y1, p.y());
  }
  x0_ -= margin_m;
  y0_ -= margin_m;
  w_ = static_cast<int>((x1 + margin_m - x0_) / res_) + 1;
  h_ = static_cast<int>((y1 + margin_m - y0_) / res_) + 1;
  fine_.assign(static_cast<size_t>(w_) * h_, 0.f);
  const int rad = static_cast<int>(std::ceil(3.0 * o.sigma_m / res_));
  std::vector<float> kernel(static_cast<size_t>((2 * rad + 1) * (2 * rad + 1)));
  for (int dy = -rad; dy <= rad; ++dy)
    for (int dx = -rad; dx <= rad; ++dx)
      kernel[static_cast<size_t>((dy + rad) * (2 * rad + 1) + dx + rad)] =
          static_cast<float>(std::exp(-0.5 * (dx * dx + dy * dy) * res_ * res_ / (o.sigma_m * o.sigma_m)));
  for (const auto& p : points) {
    const int cx = static_cast<int>(std::lround(cell_x(p.x())));
    const int cy = static_cast<int>(std::lround(cell_y(p.y())));
    for (int dy = -rad; dy <= rad; ++dy) {
      const int y = cy + dy;
      if (y < 0 || y >= h_) continue;
      for (int dx = -rad; dx <= rad; ++dx) {
        const int x = cx + dx;
        if (x < 0 || x >= w_) continue;
        float& v = fine_[static_cast<size_t>(y) * w_ + x];
        v = std::max(v, kernel[static_cast<size_t>((dy + rad) * (2 * rad + 1) + dx + rad)]);
      }
    }
  }
  // Sliding block maximum, padded by B on the low side so blocks starting left of the grid work.
  cw_ = w_ + b_;
  ch_ = h_ + b_;
  std::vector<float> rows(static_cast<size_t>(cw_) * h_, 0.f);
  for (int y = 0; y < h_; ++y)
    for (int X = 0; X < cw_; ++X) {
      float m = 0.f;
      for (int k = 0; k < b_; ++k) {
        const int x = X - b_ + k;
        if (x >= 0 && x < w_) m = std::max(m, fine_[static_cast<size_t>(y) * w_ + x]);
      }
      rows[static_cast<size_t>(y) * cw_ + X] = m;
    }
  coarse_.assign(static_cast<size_t>(cw_) * ch_, 0.f);
  for (int Y = 0; Y < ch_; ++Y)
    for (int X = 0; X < cw_; ++X) {
      float m = 0.f;
      for (int k = 0; k < b_; ++k) {
        const int y = Y - b_ + k;
        if (y >= 0 && y < h_) m = std::max(m, rows[static_cast<size_t>(y) * cw_ + X]);
      }
      coarse_[static_cast<size_t>(Y) * cw_ + X] = m;
    }
}

CorrelativeResult correlative_match(const Points& scan, const LikelihoodGrid& grid, const Pose2& guess,
                                    const CorrelativeWindow& window, const CorrelativeOptions& o, double distinct_m)
{
  CorrelativeResult best{guess, 0.0};
  if (scan.empty()) return best;
  const double res = grid.resolution();
  const int B = grid.coarse_factor();
  double dmax = 0.0;
  for (const auto& p : scan) dmax = std::max(dmax, p.norm());
  dmax = std::max(dmax, 2.0 * res);
  // The angular step moves the farthest point by about one cell.
  const double step = std::min(o.max_angular_step_deg * M_PI / 180.0,
                               std::acos(std::max(-1.0, 1.0 - res * res / (2.0 * dmax * dmax))));
  const int K = static_cast<int>(std::ceil(window.angular_rad / step));
  const int W = static_cast<int>(std::ceil(window.linear_m / res));
  const double n = static_cast<double>(scan.size());

  struct Candidate
  {
    float bound;
    int k, ox, oy;
  };
  std::vector<std::vector<int>> cells(static_cast<size_t>(2 * K + 1));  // interleaved x, y per angle
  std::vector<Candidate> candidates;
  for (int k = -K; k <= K; ++k) {
    const double th = guess.theta() + k * step;
    const double c = std::cos(th), s = std::sin(th);
    auto& cl = cells[static_cast<size_t>(k + K)];
    cl.resize(2 * scan.size());
    for (size_t i = 0; i < scan.size(); ++i) {
      const auto& q = scan[i];
      cl[2 * i] = static_cast<int>(std::lround(grid.cell_x(guess.x() + c * q.x() - s * q.y())));
      cl[2 * i + 1] = static_cast<int>(std::lround(grid.cell_y(guess.y() + s * q.x() + c * q.y())));
    }
    for (int oy = -W; oy <= W; oy += B)
      for (int ox = -W; ox <= W; ox += B) {
        double sum = 0.0;
        for (size_t i = 0; i < scan.size(); ++i) sum += grid.coarse(cl[2 * i] + ox, cl[2 * i + 1] + oy);
        candidates.push_back({static_cast<float>(sum / n), k, ox, oy});
      }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.bound != b.bound) return a.bound > b.bound;
    // Ties: prefer the smaller correction (deterministic, and closer to the guess).
    return std::abs(a.k) + std::abs(a.ox) + std::abs(a.oy) < std::abs(b.k) + std::abs(b.ox) + std::abs(b.oy);
  });
  // Branch and bound over the sorted candidates; `skip` leaves out fine translations.
  auto search = [&](const std::function<bool(int, int)>& skip, int* bk, int* bx, int* by) {
    double best_score = -1.0;
    for (const auto& cand : candidates) {
      if (cand.bound <= best_score) break;
      const auto& cl = cells[static_cast<size_t>(cand.k + K)];
      for (int oy = cand.oy; oy < cand.oy + B && oy <= W; ++oy)
        for (int ox = cand.ox; ox < cand.ox + B && ox <= W; ++ox) {
          if (skip && skip(ox, oy)) continue;
          double sum = 0.0;
          for (size_t i = 0; i < scan.size(); ++i) sum += grid.fine(cl[2 * i] + ox, cl[2 * i + 1] + oy);
          const double score = sum / n;
          if (score > best_score + 1e-12) {
            best_score = score;
            *bk = cand.k;
            *bx = ox;
            *by = oy;
          }
        }
    }
    return std::max(0.0, best_score);
  };
  int bk = 0, bx = 0, by = 0;
  best.score = search(nullptr, &bk, &bx, &by);
  best.map_from_scan = Pose2{guess.x() + bx * res, guess.y() + by * res, normalize_angle(guess.theta() + bk * step)};
  if (distinct_m > 0) {
    const double r2 = (distinct_m / res) * (distinct_m / res);
    int k2 = 0, x2 = 0, y2 = 0;
    best.runner_up = search([&](int ox, int oy) { return (ox - bx) * (ox - bx) + (oy - by) * (oy - by) < r2; }, &k2, &x2, &y2);
  }
  return best;
}

}  // namespace rgnav::scan_mapper
