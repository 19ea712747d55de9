#include "sim/sim_stereo_source.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace rgnav::sim {

namespace {

constexpr uint64_t kPeopleSalt = 4;         // the simulator's people stream (simulator.cpp)
constexpr int64_t kPeopleStepUs = 1000;     // the simulator's physics step
constexpr int64_t kLongestCatchUpUs = 10'000'000;  // a longer gap: people jump ahead 10 s at most
// The simulator's robot body band (sim.yaml robot): what people keep clear of.
const HeightBand kBodyBand{0.02, 1.2};

}  // namespace

SimStereoSource::SimStereoSource(const World& world, stereo::StereoCalibration calibration,
                                 SimStereoSourceOptions options)
    : world_(world), options_(options), renderer_(world_, std::move(calibration), options.render), scene_(world_),
      people_(world_.people, Rng::derive(options.people_seed, kPeopleSalt)), door_open_(world_.doors.size(), 1),
      error_("no SIM_TRUTH yet")
{
  for (size_t i = 0; i < world_.doors.size(); ++i) door_open_[i] = world_.doors[i].open_at(0.0) ? 1 : 0;
}

bool SimStereoSource::on_truth(int64_t utime, const Pose2& pose)
{
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) return false;
  if (last_utime_ && utime <= *last_utime_) return false;
  if (!first_utime_) first_utime_ = utime;
  if (last_utime_) {
    const Circle robot{Vec2(pose.x, pose.y), options_.robot_radius};
    auto clearance = [&](const Vec2& p, double search) { return scene_.clearance(p, search, kBodyBand, door_open_).distance; };
    for (int64_t left = std::min(utime - *last_utime_, kLongestCatchUpUs); left > 0; left -= kPeopleStepUs)
      people_.advance(static_cast<double>(std::min(left, kPeopleStepUs)) * 1e-6, robot, clearance);
  }
  last_utime_ = utime;
  pose_ = pose;
  const double t = static_cast<double>(utime - *first_utime_) * 1e-6;
  for (size_t i = 0; i < world_.doors.size(); ++i) door_open_[i] = world_.doors[i].open_at(t) ? 1 : 0;
  return true;
}

std::optional<stereo::StereoFrame> SimStereoSource::next()
{
  if (!last_utime_) {
    error_ = "no SIM_TRUTH yet";
    return std::nullopt;
  }
  if (rendered_utime_ && *rendered_utime_ == *last_utime_) {
    error_ = "no SIM_TRUTH since the last frame";
    return std::nullopt;
  }
  HeadView view;
  view.robot = pose_;
  view.pan = options_.pan;
  view.tilt = options_.tilt;
  view.door_open = door_open_;
  view.people = people_.discs();
  view.frame = static_cast<uint64_t>(rendered_);
  renderer_.render(view, &last_);
  ++rendered_;
  rendered_utime_ = last_utime_;
  error_.clear();
  if (!options_.grayscale) return stereo::StereoFrame{last_.left.image, last_.right.image, *last_utime_};
  stereo::StereoFrame frame;
  cv::cvtColor(last_.left.image, frame.left, cv::COLOR_BGR2GRAY);
  cv::cvtColor(last_.right.image, frame.right, cv::COLOR_BGR2GRAY);
  frame.utime = *last_utime_;
  return frame;
}

std::string SimStereoSource::describe() const
{
  return "simulated stereo head in " + world_.name + " (" + renderer_.calibration().source + ")";
}

}  // namespace rgnav::sim
