#include "procs/tour_runner/tour_sequencer.h"

namespace rgnav::tour_runner {

TourSequencer::TourSequencer(SequencerOptions options, std::vector<Eigen::Vector2d> targets)
    : options_(options), targets_(std::move(targets))
{}

bool TourSequencer::update(const geometry::Pose2& pose)
{
  const size_t before = next_;
  // Also skip ahead when a later target is already reached (the robot cut a corner).
  for (size_t k = next_; k < targets_.size() && k < next_ + static_cast<size_t>(options_.lookahead); ++k) {
    if ((targets_[k] - pose.translation()).norm() <= options_.reach_radius) next_ = k + 1;
  }
  return next_ != before;
}

std::vector<Eigen::Vector2d> TourSequencer::upcoming() const
{
  std::vector<Eigen::Vector2d> out;
  for (size_t k = next_; k < targets_.size() && out.size() < static_cast<size_t>(options_.lookahead); ++k)
    out.push_back(targets_[k]);
  return out;
}

}  // namespace rgnav::tour_runner
