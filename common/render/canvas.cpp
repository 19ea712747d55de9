#include "render/canvas.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rgnav::render {
namespace {

constexpr double kMargin = 0.5;  // [m]

struct Frame
{
  Frame(const Bounds& b, double ppm) : bounds(b), ppm(ppm)
  {
    width = static_cast<int>((b.max.x() - b.min.x() + 2 * kMargin) * ppm) + 1;
    height = static_cast<int>((b.max.y() - b.min.y() + 2 * kMargin) * ppm) + 1;
  }
  // Map metres (y up) -> picture pixels (y down).
  Eigen::Vector2d px(const Eigen::Vector2d& p) const
  {
    return {(p.x() - bounds.min.x() + kMargin) * ppm, (bounds.max.y() + kMargin - p.y()) * ppm};
  }
  Bounds bounds;
  double ppm;
  int width, height;
};

std::string rgb(Color c)
{
  std::ostringstream s;
  s << "rgb(" << int(c[0]) << "," << int(c[1]) << "," << int(c[2]) << ")";
  return s.str();
}

std::string escape(const std::string& in)
{
  std::string out;
  for (char ch : in) {
    if (ch == '<') out += "&lt;";
    else if (ch == '>') out += "&gt;";
    else if (ch == '&') out += "&amp;";
    else out += ch;
  }
  return out;
}

class SvgCanvas final : public Canvas
{
 public:
  SvgCanvas(const Bounds& b, double ppm) : f_(b, ppm) {}
  void polygon(const std::vector<Eigen::Vector2d>& pts, Color fill, double opacity) override
  {
    body_ << "<polygon points=\"";
    for (const auto& p : pts) {
      const auto q = f_.px(p);
      body_ << q.x() << "," << q.y() << " ";
    }
    body_ << "\" fill=\"" << rgb(fill) << "\" fill-opacity=\"" << opacity << "\" stroke=\"none\"/>\n";
  }
  void line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Color c, double w, bool dashed) override
  {
    const auto p = f_.px(a), q = f_.px(b);
    body_ << "<line x1=\"" << p.x() << "\" y1=\"" << p.y() << "\" x2=\"" << q.x() << "\" y2=\"" << q.y()
          << "\" stroke=\"" << rgb(c) << "\" stroke-width=\"" << w << "\"" << (dashed ? " stroke-dasharray=\"6,4\"" : "")
          << " stroke-linecap=\"round\"/>\n";
  }
  void circle(const Eigen::Vector2d& c, double r, Color fill) override
  {
    const auto p = f_.px(c);
    body_ << "<circle cx=\"" << p.x() << "\" cy=\"" << p.y() << "\" r=\"" << r << "\" fill=\"" << rgb(fill) << "\"/>\n";
  }
  void text(const Eigen::Vector2d& at, const std::string& s, Color c, double size) override
  {
    const auto p = f_.px(at);
    body_ << "<text x=\"" << p.x() << "\" y=\"" << p.y() << "\" font-family=\"sans-serif\" font-size=\"" << size
          << "\" fill=\"" << rgb(c) << "\">" << escape(s) << "</text>\n";
  }
  void save(const std::string& path) override
  {
    std::ofstream out(path);
    out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << f_.width << "\" height=\"" << f_.height
        << "\" viewBox=\"0 0 " << f_.width << " " << f_.height << "\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        << body_.str() << "</svg>\n";
    if (!out) throw std::runtime_error("cannot write " + path);
  }

 private:
  Frame f_;
  std::ostringstream body_;
};

class RasterCanvas final : public Canvas
{
 public:
  RasterCanvas(const Bounds& b, double ppm) : f_(b, ppm), img_(f_.height, f_.width, CV_8UC3, cv::Scalar(255, 255, 255)) {}
  static cv::Scalar bgr(Color c) { return cv::Scalar(c[2], c[1], c[0]); }
  cv::Point pt(const Eigen::Vector2d& p) const
  {
    const auto q = f_.px(p);
    return {static_cast<int>(std::lround(q.x())), static_cast<int>(std::lround(q.y()))};
  }
  void polygon(const std::vector<Eigen::Vector2d>& pts, Color fill, double opacity) override
  {
    std::vector<cv::Point> poly;
    for (const auto& p : pts) poly.push_back(pt(p));
    // Fills come first in every picture, on the white background: blending the colour with
    // white once is the same as alpha blending, without copying the image per polygon.
    Color blended;
    for (int i = 0; i < 3; ++i) blended[i] = static_cast<uint8_t>(std::lround(255.0 * (1.0 - opacity) + fill[i] * opacity));
    cv::fillPoly(img_, std::vector<std::vector<cv::Point>>{poly}, bgr(blended));
  }
  void line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Color c, double w, bool dashed) override
  {
    const int t = std::max(1, static_cast<int>(std::lround(w)));
    if (!dashed) {
      cv::line(img_, pt(a), pt(b), bgr(c), t, cv::LINE_AA);
      return;
    }
    const double len_px = (f_.px(b) - f_.px(a)).norm();
    const int dashes = std::max(1, static_cast<int>(len_px / 10));
    for (int k = 0; k < dashes; k += 2)
      cv::line(img_, pt(a + (b - a) * (double(k) / dashes)), pt(a + (b - a) * (double(k + 1) / dashes)), bgr(c), t, cv::LINE_AA);
  }
  void circle(const Eigen::Vector2d& c, double r, Color fill) override
  {
    cv::circle(img_, pt(c), std::max(1, static_cast<int>(std::lround(r))), bgr(fill), cv::FILLED, cv::LINE_AA);
  }
  void text(const Eigen::Vector2d& at, const std::string& s, Color c, double size) override
  {
    cv::putText(img_, s, pt(at), cv::FONT_HERSHEY_SIMPLEX, size / 30.0, bgr(c), 1, cv::LINE_AA);
  }
  void save(const std::string& path) override
  {
    if (!cv::imwrite(path, img_)) throw std::runtime_error("cannot write " + path);
  }

 private:
  Frame f_;
  cv::Mat img_;
};

}  // namespace

std::unique_ptr<Canvas> make_svg_canvas(const Bounds& b, double ppm) { return std::make_unique<SvgCanvas>(b, ppm); }
std::unique_ptr<Canvas> make_raster_canvas(const Bounds& b, double ppm) { return std::make_unique<RasterCanvas>(b, ppm); }

std::unique_ptr<Canvas> make_canvas_for(const std::string& path, const Bounds& b, double ppm)
{
  if (path.size() >= 4 && path.substr(path.size() - 4) == ".svg") return make_svg_canvas(b, ppm);
  return make_raster_canvas(b, ppm);
}

}  // namespace rgnav::render
