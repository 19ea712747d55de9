// Synthetic worlds for tests: walls as segments and an exact ray caster over them. One fixture
// for every test that needs a laser's view of a made-up world (the scan mapper's, the RG
// kernel's, the gateway detector's and collision avoidance's); each turns the ranges into its
// own scan type. Plain geometry: no LCM, so algorithm tests can link it.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace rgnav::testing {

struct Wall
{
  Eigen::Vector2d a, b;
};
using Walls = std::vector<Wall>;

// The four sides of the axis-aligned box [x0, x1] x [y0, y1], counter-clockwise from (x0, y0).
Walls box(double x0, double y0, double x1, double y1);
// Appends `more` to `walls`.
void add(Walls* walls, const Walls& more);

// Distance along the ray o + t * d (d a unit vector) to the nearest wall it meets at t > min_t;
// infinity if it meets none. A wall within 1e-12 of parallel to the ray is not met; a ray
// through a wall's end point meets it.
double nearest_wall(const Walls& walls, const Eigen::Vector2d& o, const Eigen::Vector2d& d, double min_t = 0.0);

}  // namespace rgnav::testing
