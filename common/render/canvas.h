// A minimal drawing surface in map coordinates (metres, y up), with an SVG and a raster
// (OpenCV, PNG) implementation, so that one drawing routine makes both kinds of picture.
#pragma once

#include <Eigen/Core>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace rgnav::render {

using Color = std::array<uint8_t, 3>;  // R, G, B

struct Bounds
{
  Eigen::Vector2d min{0, 0}, max{1, 1};
};

class Canvas
{
 public:
  virtual ~Canvas() = default;
  virtual void polygon(const std::vector<Eigen::Vector2d>& pts, Color fill, double opacity) = 0;
  virtual void line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Color color, double width_px, bool dashed) = 0;
  virtual void circle(const Eigen::Vector2d& c, double radius_px, Color fill) = 0;
  virtual void text(const Eigen::Vector2d& at, const std::string& s, Color color, double size_px) = 0;
  // Writes the picture; throws std::runtime_error on failure.
  virtual void save(const std::string& path) = 0;
};

// pixels_per_metre scales the picture; a margin of 0.5 m is added around bounds.
std::unique_ptr<Canvas> make_svg_canvas(const Bounds& bounds, double pixels_per_metre);
std::unique_ptr<Canvas> make_raster_canvas(const Bounds& bounds, double pixels_per_metre);
// By file extension: .svg or .png (anything OpenCV writes).
std::unique_ptr<Canvas> make_canvas_for(const std::string& path, const Bounds& bounds, double pixels_per_metre);

}  // namespace rgnav::render
