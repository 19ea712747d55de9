// rgnav_rect_detect: the rectangle detector on one rectified stereo pair (PNG files), for a person
// to look at: prints each rectangle (camera frame) and draws the quadrangles into a picture.
//
//   rgnav_rect_detect LEFT.png RIGHT.png --focal 500 --baseline 0.12 [--out detected.png] [--segments]
#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <iostream>

#include "vision/dense_stereo.h"
#include "vision/rectangle_detector.h"

int main(int argc, char** argv)
{
  using namespace rgnav::vision;
  CLI::App app{"3D rectangles in one rectified stereo pair"};
  std::string left_file, right_file, out_file;
  double focal = 500.0, baseline = 0.12;
  int downscale = 1;
  app.add_option("left", left_file)->required();
  app.add_option("right", right_file)->required();
  app.add_option("--focal", focal, "[px] rectified focal length");
  app.add_option("--baseline", baseline, "[m]");
  app.add_option("--downscale", downscale, "disparity at 1/N resolution");
  app.add_option("--out", out_file, "picture of the quadrangles found");
  bool draw_segments = false;
  app.add_flag("--segments", draw_segments, "also print and draw the merged line segments (blue)");
  CLI11_PARSE(app, argc, argv);
  const cv::Mat left = cv::imread(left_file, cv::IMREAD_GRAYSCALE), right = cv::imread(right_file, cv::IMREAD_GRAYSCALE);
  if (left.empty() || right.empty()) {
    std::cerr << "cannot read the pair\n";
    return 2;
  }
  DisparityOptions d;
  d.downscale = downscale;
  d.num_disparities = 96;
  const cv::Mat disparity = DenseStereo(d).disparity(left, right);
  const Pinhole cam{focal, focal, (left.cols - 1) / 2.0, (left.rows - 1) / 2.0};
  RectangleDetectorOptions o;
  o.refine.focal_baseline = focal * baseline;
  const auto segments = merge_segments(detect_segments(left), o.quadrangles);
  const auto quads = group_quadrangles(segments, o.quadrangles);
  const auto rects = detect_rectangles(left, disparity, downscale, cam, o);
  std::cout << quads.size() << " quadrangles, " << rects.size() << " rectangles\n";
  cv::Mat pic;
  cv::cvtColor(left, pic, cv::COLOR_GRAY2BGR);
  if (draw_segments)
    for (const auto& sg : segments) std::cout << "segment " << sg.a.transpose() << " " << sg.b.transpose() << "\n";
  if (draw_segments)
    for (const auto& sg : segments) cv::line(pic, cv::Point2d(sg.a.x(), sg.a.y()), cv::Point2d(sg.b.x(), sg.b.y()), {255, 80, 0}, 1);
  for (const auto& q : quads)
    for (int i = 0; i < 4; ++i)
      cv::line(pic, cv::Point2d(q[i].x(), q[i].y()), cv::Point2d(q[(i + 1) % 4].x(), q[(i + 1) % 4].y()), {0, 0, 160}, 1);
  for (const auto& r : rects) {
    std::cout << "sides " << r.camera.side_a << " x " << r.camera.side_b << " m, support " << r.support << ", normal "
              << r.camera.normal.transpose() << ", corner0 " << r.camera.corners[0].transpose() << "\n";
    for (int i = 0; i < 4; ++i)
      cv::line(pic, cv::Point2d(r.image[i].x(), r.image[i].y()), cv::Point2d(r.image[(i + 1) % 4].x(), r.image[(i + 1) % 4].y()),
               {0, 255, 0}, 2);
  }
  if (!out_file.empty()) cv::imwrite(out_file, pic);
  return 0;
}
