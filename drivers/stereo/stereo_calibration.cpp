#include "drivers/stereo/stereo_calibration.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <stdexcept>

#include "config/config.h"
#include "config/file_checks.h"

namespace rgnav::stereo {

namespace {

using config::ConfigError;

const std::set<std::string> kRequired = {"image_width", "image_height", "M1", "D1", "M2", "D2", "R", "T",
                                         "base_from_head", "head_from_left_camera_xyz", "head_from_left_camera_rpy"};
// Written by calibration tools (stereo_calib's extrinsics); readers rectify from M, D, R, T.
const std::set<std::string> kOptional = {"R1", "R2", "P1", "P2", "Q"};

[[noreturn]] void fail(const std::string& path, const std::string& key, const std::string& what)
{
  throw ConfigError(path + ": " + (key.empty() ? "" : "key '" + key + "': ") + what);
}

// A CV_64F matrix of rows x cols (cols 0: a row or column vector of any listed length).
cv::Mat read_matrix(const cv::FileStorage& fs, const std::string& path, const std::string& key, int rows, int cols)
{
  const cv::FileNode n = fs[key];
  if (n.empty() || n.isNone()) fail(path, key, "required matrix missing");
  cv::Mat m;
  try {
    n >> m;
  } catch (const cv::Exception& e) {
    fail(path, key, std::string("not an opencv-matrix: ") + e.what());
  }
  if (m.empty()) fail(path, key, "not an opencv-matrix (rows, cols, dt, data)");
  if (m.channels() != 1) fail(path, key, "expected a single-channel matrix");
  m.convertTo(m, CV_64F);
  if (cols > 0 && (m.rows != rows || m.cols != cols))
    fail(path, key, "expected " + std::to_string(rows) + "x" + std::to_string(cols) + ", got " +
                        std::to_string(m.rows) + "x" + std::to_string(m.cols));
  if (!cv::checkRange(m)) fail(path, key, "values must be finite");
  return m;
}

int read_int(const cv::FileStorage& fs, const std::string& path, const std::string& key, int min, int max)
{
  const cv::FileNode n = fs[key];
  if (n.empty() || n.isNone()) fail(path, key, "required integer missing");
  if (!n.isInt()) fail(path, key, "expected an integer");
  const int v = static_cast<int>(n);
  if (v < min || v > max) fail(path, key, "must be within [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  return v;
}

cv::Matx33d camera_matrix(const cv::FileStorage& fs, const std::string& path, const std::string& key, cv::Size size)
{
  const cv::Matx33d m = read_matrix(fs, path, key, 3, 3);
  if (!(m(0, 0) > 0 && m(1, 1) > 0)) fail(path, key, "focal lengths fx, fy must be positive");
  if (m(0, 2) < 0 || m(0, 2) > size.width || m(1, 2) < 0 || m(1, 2) > size.height)
    fail(path, key, "principal point must lie inside the image");
  if (m(1, 0) != 0 || m(2, 0) != 0 || m(2, 1) != 0 || m(2, 2) != 1) fail(path, key, "expected [fx s cx; 0 fy cy; 0 0 1]");
  return m;
}

cv::Mat distortion(const cv::FileStorage& fs, const std::string& path, const std::string& key)
{
  cv::Mat d = read_matrix(fs, path, key, 0, 0);
  if (d.rows != 1 && d.cols != 1) fail(path, key, "expected a row or column of coefficients");
  d = d.reshape(1, 1);
  const int n = d.cols;
  if (n != 4 && n != 5 && n != 8 && n != 12 && n != 14) fail(path, key, "expected 4, 5, 8, 12 or 14 coefficients");
  return d;
}

Eigen::Vector3d vector3(const cv::FileStorage& fs, const std::string& path, const std::string& key, double limit)
{
  const cv::Mat m = read_matrix(fs, path, key, 0, 0);
  if (m.total() != 3) fail(path, key, "expected 3 values");
  const Eigen::Vector3d v(m.at<double>(0), m.at<double>(1), m.at<double>(2));
  if (v.cwiseAbs().maxCoeff() > limit) fail(path, key, "values must be within +-" + std::to_string(limit));
  return v;
}

}  // namespace

StereoCalibration load_stereo_calibration(const std::string& path)
{
  const std::string text = config::read_text_file(path, "stereo calibration");
  if (text.rfind("%YAML", 0) != 0) fail(path, "", "not an OpenCV YAML file (it must start with %YAML:1.0)");
  cv::FileStorage fs;
  try {
    fs.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  } catch (const cv::Exception& e) {
    fail(path, "", std::string("not OpenCV YAML: ") + e.what());
  }
  if (!fs.isOpened() || !fs.root().isMap()) fail(path, "", "not OpenCV YAML (a mapping of keys)");
  for (const auto& node : fs.root())
    if (!kRequired.count(node.name()) && !kOptional.count(node.name())) fail(path, node.name(), "unknown key");

  StereoCalibration c;
  c.source = path;
  c.image_size.width = read_int(fs, path, "image_width", 16, 8192);
  c.image_size.height = read_int(fs, path, "image_height", 16, 8192);
  c.M1 = camera_matrix(fs, path, "M1", c.image_size);
  c.M2 = camera_matrix(fs, path, "M2", c.image_size);
  c.D1 = distortion(fs, path, "D1");
  c.D2 = distortion(fs, path, "D2");
  c.R = read_matrix(fs, path, "R", 3, 3);
  const cv::Matx33d should_be_identity = c.R.t() * c.R;
  if (cv::norm(should_be_identity - cv::Matx33d::eye(), cv::NORM_INF) > 1e-4 || cv::determinant(c.R) < 0)
    fail(path, "R", "must be a rotation (orthonormal, determinant +1)");
  const cv::Mat t = read_matrix(fs, path, "T", 0, 0);
  if (t.total() != 3) fail(path, "T", "expected 3 values");
  c.T = cv::Vec3d(t.at<double>(0), t.at<double>(1), t.at<double>(2));
  if (!(c.baseline() > 0.01 && c.baseline() <= 2.0)) fail(path, "T", "baseline must be within (0.01, 2] m (T is in metres)");
  c.base_from_head = vector3(fs, path, "base_from_head", 5.0);
  c.head_from_left_camera_xyz = vector3(fs, path, "head_from_left_camera_xyz", 1.0);
  c.head_from_left_camera_rpy = vector3(fs, path, "head_from_left_camera_rpy", M_PI);
  return c;
}

std::string stereo_calibration_text(const StereoCalibration& c, const std::string& comment,
                                    const StereoRectification& rectification)
{
  cv::FileStorage fs(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  const auto vec3 = [](const Eigen::Vector3d& v) { return cv::Mat(cv::Matx31d(v.x(), v.y(), v.z())); };
  fs << "image_width" << c.image_size.width << "image_height" << c.image_size.height;
  fs << "M1" << cv::Mat(c.M1) << "D1" << c.D1 << "M2" << cv::Mat(c.M2) << "D2" << c.D2;
  fs << "R" << cv::Mat(c.R) << "T" << cv::Mat(cv::Matx31d(c.T[0], c.T[1], c.T[2]));
  const std::pair<const char*, const cv::Mat*> rect[] = {{"R1", &rectification.R1}, {"R2", &rectification.R2},
                                                          {"P1", &rectification.P1}, {"P2", &rectification.P2},
                                                          {"Q", &rectification.Q}};
  for (const auto& [key, m] : rect)
    if (!m->empty()) fs << key << *m;
  fs << "base_from_head" << vec3(c.base_from_head) << "head_from_left_camera_xyz" << vec3(c.head_from_left_camera_xyz)
     << "head_from_left_camera_rpy" << vec3(c.head_from_left_camera_rpy);
  std::string body = fs.releaseAndGetString();
  // OpenCV writes "%YAML:1.0\n---\n..."; the comment goes between the two, as in the shipped files.
  const size_t first = body.find('\n');
  std::string text = body.substr(0, first + 1);
  size_t from = 0;
  while (from <= comment.size() && !comment.empty()) {
    const size_t end = comment.find('\n', from);
    const std::string line = comment.substr(from, end == std::string::npos ? std::string::npos : end - from);
    text += line.empty() ? "#\n" : "# " + line + "\n";
    if (end == std::string::npos) break;
    from = end + 1;
  }
  return text + body.substr(first + 1);
}

void write_stereo_calibration(const std::string& path, const StereoCalibration& c, const std::string& comment,
                              const StereoRectification& rectification)
{
  const std::string text = stereo_calibration_text(c, comment, rectification);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << text;
    if (!out.flush()) throw std::runtime_error(tmp + ": cannot be written");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error(path + ": cannot be written (rename failed)");
}

std::string stereo_calibration_path(const std::string& config_dir, const std::string& id)
{
  if (id.empty() || id == "." || id == "..") throw ConfigError("calibration id '" + id + "' is not a file name");
  for (const char ch : id)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.'))
      throw ConfigError("calibration id '" + id + "': only letters, digits, '_', '-' and '.' are allowed");
  return config_dir + "/stereo/" + id + ".yml";
}

Eigen::Matrix3d head_from_optical_nominal()
{
  Eigen::Matrix3d r;
  r.col(0) = Eigen::Vector3d(0, -1, 0);  // image x: to the right = head -y
  r.col(1) = Eigen::Vector3d(0, 0, -1);  // image y: down = head -z
  r.col(2) = Eigen::Vector3d(1, 0, 0);   // optical axis: forward = head x
  return r;
}

Eigen::Isometry3d base_from_left_camera(const StereoCalibration& c, double pan, double tilt)
{
  Eigen::Isometry3d base_from_head = Eigen::Isometry3d::Identity();
  base_from_head.translation() = c.base_from_head;
  // Tilt + looks up: a rotation about +y by -tilt lifts the x axis.
  base_from_head.linear() =
      (Eigen::AngleAxisd(pan, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-tilt, Eigen::Vector3d::UnitY())).toRotationMatrix();
  const Eigen::Vector3d& rpy = c.head_from_left_camera_rpy;
  Eigen::Isometry3d head_from_camera = Eigen::Isometry3d::Identity();
  head_from_camera.translation() = c.head_from_left_camera_xyz;
  head_from_camera.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix() *
                              head_from_optical_nominal();
  return base_from_head * head_from_camera;
}

Eigen::Isometry3d left_from_right_camera(const StereoCalibration& c)
{
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = c.R(i, j);
  Eigen::Isometry3d right_from_left = Eigen::Isometry3d::Identity();
  right_from_left.linear() = r;
  right_from_left.translation() = Eigen::Vector3d(c.T[0], c.T[1], c.T[2]);
  return right_from_left.inverse();
}

}  // namespace rgnav::stereo
