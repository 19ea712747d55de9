// Geometry as the page's JSON frames carry it: millimetres and milliradians (all the page can
// show; shorter frames), poses as [x, y, theta], point lists flat [x0, y0, x1, y1, ...].
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cmath>

#include "geometry/pose2.h"

namespace rgnav::viewer {

inline double r3(double v) { return std::round(v * 1000.0) / 1000.0; }

inline nlohmann::json pose_array(const geometry::Pose2& p) { return nlohmann::json::array({r3(p.x()), r3(p.y()), r3(p.theta())}); }

inline void append_point(nlohmann::json& flat, const Eigen::Vector2d& p)
{
  flat.push_back(r3(p.x()));
  flat.push_back(r3(p.y()));
}

}  // namespace rgnav::viewer
