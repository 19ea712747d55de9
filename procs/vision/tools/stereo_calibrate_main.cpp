// rgnav_stereo_calibrate: calibrates a stereo rig from chessboard pairs and writes its calibration
// file (config/stereo/<calibration_id>.yml, the format drivers/stereo/stereo_calibration.h loads).
//   rgnav_stereo_calibrate --images DIR --out FILE [--board 9x6] [--square 0.025] [--report FILE]
// Pairs: every image in DIR whose name holds the left token (default "left") with the file of the
// same name with the right token; pairs where either view does not show the whole board are
// skipped (and named). Where the rig sits on the robot comes from the robot description: the head
// at stereo.base_from_head, head_height_m up; the left camera half the measured baseline to the
// left of the head's centre, mounted nominally (optical axis forward). Prints the RMS
// reprojection error; --report writes it and the rest as JSON.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "chessboard_calibration.h"
#include "config/robot_description.h"
#include "runtime/process_main.h"

namespace fs = std::filesystem;
using namespace rgnav;

namespace {

bool is_image(const fs::path& p)
{
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".jpg" || ext == ".jpeg" || ext == ".png" || ext == ".pgm" || ext == ".ppm" || ext == ".bmp";
}

cv::Size parse_board(const std::string& text)
{
  int w = 0, h = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || x != 'x' || w < 2 || h < 2 || !in.eof())
    throw std::invalid_argument("--board: expected WxH inner corners (e.g. 9x6), got '" + text + "'");
  return {w, h};
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"stereo calibration from chessboard pairs -> an OpenCV stereo_calib file"};
  std::string dir = runtime::default_data_dir() + "/stereo/chessboard", out, report, board_text = "9x6";
  std::string left_token = "left", right_token = "right";
  std::string robot_file = runtime::default_config_dir() + "/robot.yaml";
  double square = 0.025;
  app.add_option("--images", dir, "folder of chessboard pairs");
  app.add_option("--out", out, "calibration file to write")->required();
  app.add_option("--report", report, "JSON report (RMS, per-camera RMS, epipolar error, pairs used)");
  app.add_option("--board", board_text, "inner corners WxH");
  app.add_option("--square", square, "square edge [m]: the scale of T")->check(CLI::PositiveNumber);
  app.add_option("--left-token", left_token);
  app.add_option("--right-token", right_token);
  app.add_option("--robot", robot_file, "robot description (where the head sits)");
  CLI11_PARSE(app, argc, argv);
  try {
    vision::tools::ChessboardOptions o;
    o.inner_corners = parse_board(board_text);
    o.square_size = square;
    std::vector<fs::path> lefts;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && is_image(e.path()) && e.path().filename().string().find(left_token) != std::string::npos)
        lefts.push_back(e.path());
    std::sort(lefts.begin(), lefts.end());
    std::vector<vision::tools::ChessboardPair> pairs;
    std::vector<std::string> skipped;
    cv::Size size;
    for (const auto& l : lefts) {
      std::string name = l.filename().string();
      name.replace(name.find(left_token), left_token.size(), right_token);
      const fs::path r = l.parent_path() / name;
      const cv::Mat left = cv::imread(l.string(), cv::IMREAD_GRAYSCALE), right = cv::imread(r.string(), cv::IMREAD_GRAYSCALE);
      if (left.empty() || right.empty()) {
        skipped.push_back(l.filename().string() + " (no readable partner " + name + ")");
        continue;
      }
      if (size.area() == 0) size = left.size();
      if (left.size() != size || right.size() != size) {
        skipped.push_back(l.filename().string() + " (size differs)");
        continue;
      }
      const auto cl = vision::tools::find_chessboard(left, o.inner_corners);
      const auto cr = vision::tools::find_chessboard(right, o.inner_corners);
      if (!cl || !cr) {
        skipped.push_back(l.filename().string() + " (board not found in " + (cl ? "right" : "left") + ")");
        continue;
      }
      pairs.push_back({l.filename().string(), *cl, *cr});
    }
    auto r = vision::tools::calibrate_stereo(pairs, size, o);
    const auto robot = config::load_robot_description_file(robot_file);
    stereo::StereoCalibration& c = r.calibration;
    c.base_from_head = Eigen::Vector3d(robot.stereo.base_from_head.x(), robot.stereo.base_from_head.y(), robot.stereo.height);
    c.head_from_left_camera_xyz = Eigen::Vector3d(0.0, 0.5 * c.baseline(), 0.0);
    c.head_from_left_camera_rpy = Eigen::Vector3d::Zero();
    std::ostringstream comment;
    comment << std::setprecision(3) << "Stereo calibration of a real rig, written by rgnav_stereo_calibrate (procs/vision/tools)\n"
            << "from " << r.pairs << " chessboard pairs in " << fs::path(dir).filename().string() << "/ (" << o.inner_corners.width
            << "x" << o.inner_corners.height << " inner corners, squares of " << square << " m assumed:\n"
            << "T is in metres only as far as that square size is right).\n"
            << "cv::stereoCalibrate RMS reprojection error " << r.rms_px << " px (each camera alone " << r.left_rms_px << " / "
            << r.right_rms_px << " px),\n"
            << "mean epipolar error " << r.epipolar_error_px << " px. Keys: see config/stereo/sim_b21r_head.yml.\n"
            << "Mounting (base_from_head, head_from_left_camera_*): the robot description's head, the left\n"
            << "camera half the baseline left of its centre, nominal orientation; not measured.";
    stereo::write_stereo_calibration(out, c, comment.str(), {r.R1, r.R2, r.P1, r.P2, r.Q});
    // What is written must load (the loader's checks are the product's).
    const auto loaded = stereo::load_stereo_calibration(out);
    nlohmann::json j = {{"calib_reprojection_px", r.rms_px},
                        {"left_rms_px", r.left_rms_px},
                        {"right_rms_px", r.right_rms_px},
                        {"epipolar_error_px", r.epipolar_error_px},
                        {"pairs", r.pairs},
                        {"skipped", skipped},
                        {"square_size_m", square},
                        {"board", {o.inner_corners.width, o.inner_corners.height}},
                        {"image_size", {size.width, size.height}},
                        {"baseline_m", loaded.baseline()},
                        {"focal_px", {loaded.M1(0, 0), loaded.M1(1, 1), loaded.M2(0, 0), loaded.M2(1, 1)}},
                        {"out", out}};
    if (!report.empty()) std::ofstream(report) << j.dump(2) << "\n";
    std::cout << "rgnav_stereo_calibrate: " << r.pairs << " pairs (" << skipped.size() << " skipped), RMS " << r.rms_px
              << " px, baseline " << loaded.baseline() << " m -> " << out << "\n";
    for (const auto& s : skipped) std::cout << "  skipped " << s << "\n";
  } catch (const std::exception& e) {
    std::cerr << "rgnav_stereo_calibrate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
