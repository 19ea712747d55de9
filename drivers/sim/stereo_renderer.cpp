#include "sim/stereo_renderer.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rgnav::sim {

namespace {

// A face in camera coordinates, with what the per-pixel work needs.
struct CameraFace
{
  Eigen::Vector3d u, v, n;  // axes and normal (u x v) in the camera frame
  double ou = 0, ov = 0;    // origin . u, origin . v (the origin's own texture offset)
  double d = 0;             // n . origin: the plane n . X = d
  const Face* face = nullptr;
  SurfaceLook look;
};

// Lambert-like shading from a fixed light, so faces of different orientation differ in brightness
// as they do under room lights.
float shade_of(const Face& f)
{
  static const Eigen::Vector3d light = Eigen::Vector3d(0.35, 0.55, 0.76).normalized();
  const Eigen::Vector3d n = f.u.cross(f.v);
  return static_cast<float>(0.72 + 0.28 * std::fabs(n.dot(light)));
}

// Clips the polygon to z >= near (Sutherland-Hodgman against one plane).
int clip_near(const Eigen::Vector3d* in, int n, double near, Eigen::Vector3d* out)
{
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d& a = in[i];
    const Eigen::Vector3d& b = in[(i + 1) % n];
    const bool ain = a.z() >= near, bin = b.z() >= near;
    if (ain) out[m++] = a;
    if (ain != bin) out[m++] = a + (b - a) * ((near - a.z()) / (b.z() - a.z()));
  }
  return m;
}

uint64_t noise_seed(uint64_t seed, uint64_t frame, uint64_t camera)
{
  uint64_t z = seed * 0x9E3779B97F4A7C15ull + frame * 0xBF58476D1CE4E5B9ull + camera * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return z ? z : 1;
}

// For each distorted pixel, the ideal (pinhole, same camera matrix) pixel it shows.
void distortion_maps(const cv::Matx33d& K, const cv::Mat& D, cv::Size size, cv::Mat* map_x, cv::Mat* map_y)
{
  std::vector<cv::Point2f> pixels;
  pixels.reserve(static_cast<size_t>(size.area()));
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x) pixels.emplace_back(static_cast<float>(x), static_cast<float>(y));
  std::vector<cv::Point2f> ideal;
  cv::undistortPoints(pixels, ideal, K, D, cv::noArray(), K);
  map_x->create(size, CV_32F);
  map_y->create(size, CV_32F);
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x) {
      const cv::Point2f& p = ideal[static_cast<size_t>(y * size.width + x)];
      map_x->at<float>(y, x) = p.x;
      map_y->at<float>(y, x) = p.y;
    }
}

// `m` as an H x W matrix of `type` that nothing else holds (a buffer still held elsewhere, e.g.
// by a frame handed out earlier, is left to its holder).
void own(cv::Mat* m, int H, int W, int type)
{
  if (m->u && m->u->refcount > 1) m->release();
  m->create(H, W, type);
}

Eigen::Isometry3d world_from_base(const Pose2& p)
{
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(p.x, p.y, 0);
  t.linear() = Eigen::AngleAxisd(p.theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return t;
}

}  // namespace

StereoRenderer::StereoRenderer(const World& world, stereo::StereoCalibration calibration, StereoRenderOptions options)
    : world_(world), calibration_(std::move(calibration)), options_(options), static_faces_(static_faces(world_)),
      texture_(world_.texture_seed)
{
  if (calibration_.M1(0, 1) != 0 || calibration_.M2(0, 1) != 0)
    throw std::invalid_argument(calibration_.source + ": the simulated head draws cameras without skew (M(0,1) = 0)");
  if (options_.noise_sigma > 0) {
    // Frames take windows of one seeded bank (drawing 2 x 0.9 M normal numbers per frame would
    // cost more than the rendering); windows start up to 2^16 values apart.
    noise_bank_.create(1, calibration_.image_size.area() * 3 + (1 << 16), CV_16S);
    cv::RNG rng(options_.noise_seed);
    rng.fill(noise_bank_, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(options_.noise_sigma));
  }
  if (calibration_.has_distortion()) {
    distortion_maps(calibration_.M1, calibration_.D1, calibration_.image_size, &left_map_x_, &left_map_y_);
    distortion_maps(calibration_.M2, calibration_.D2, calibration_.image_size, &right_map_x_, &right_map_y_);
  }
}

Eigen::Isometry3d StereoRenderer::world_from_left_camera(const HeadView& view) const
{
  return world_from_base(view.robot) * stereo::base_from_left_camera(calibration_, view.pan, view.tilt);
}

StereoRender StereoRenderer::render(const HeadView& view) const
{
  StereoRender r;
  render(view, &r);
  return r;
}

void StereoRenderer::render(const HeadView& view, StereoRender* out) const
{
  std::vector<uint8_t> door_open = view.door_open;
  for (size_t i = door_open.size(); i < world_.doors.size(); ++i) door_open.push_back(world_.doors[i].open ? 1 : 0);
  std::vector<Face> dynamic;
  append_dynamic_faces(world_, door_open, view.people, &dynamic);
  const std::vector<const std::vector<Face>*> sets = {&static_faces_, &dynamic};
  const Eigen::Isometry3d left_pose = world_from_left_camera(view);
  draw(sets, left_pose, calibration_.M1, &out->left);
  draw(sets, left_pose * stereo::left_from_right_camera(calibration_), calibration_.M2, &out->right);
  finish(&out->left, left_map_x_, left_map_y_, noise_seed(options_.noise_seed, view.frame, 1));
  finish(&out->right, right_map_x_, right_map_y_, noise_seed(options_.noise_seed, view.frame, 2));
}

CameraRender StereoRenderer::render_camera(const Eigen::Isometry3d& world_from_camera, const cv::Matx33d& K,
                                           const std::vector<Face>& extra) const
{
  CameraRender out;
  draw({&static_faces_, &extra}, world_from_camera, K, &out);
  return out;
}

void StereoRenderer::finish(CameraRender* r, const cv::Mat& map_x, const cv::Mat& map_y, uint64_t noise_key) const
{
  if (!map_x.empty()) {
    cv::Mat image, depth;
    cv::remap(r->image, image, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar::all(0));
    cv::remap(r->depth, depth, map_x, map_y, cv::INTER_NEAREST, cv::BORDER_CONSTANT, cv::Scalar::all(0));
    r->image = image;
    r->depth = depth;
  }
  if (!noise_bank_.empty()) {
    // A window of the seeded noise bank, placed by the frame's key.
    const int n = static_cast<int>(r->image.total()) * 3;
    const int offset = static_cast<int>(noise_key % static_cast<uint64_t>(noise_bank_.cols - n + 1));
    const int16_t* noise = noise_bank_.ptr<int16_t>(0) + offset;
    uchar* p = r->image.ptr<uchar>(0);
    for (int i = 0; i < n; ++i) p[i] = cv::saturate_cast<uchar>(p[i] + noise[i]);
  }
}

void StereoRenderer::draw(const std::vector<const std::vector<Face>*>& face_sets,
                          const Eigen::Isometry3d& world_from_camera, const cv::Matx33d& K, CameraRender* out) const
{
  const int W = calibration_.image_size.width, H = calibration_.image_size.height;
  const double fx = K(0, 0), fy = K(1, 1), cx = K(0, 2), cy = K(1, 2);
  const double near = options_.near;
  const Eigen::Isometry3d camera_from_world = world_from_camera.inverse();
  const Eigen::Matrix3d R = camera_from_world.linear();

  // Pass 1: nearest face per pixel (depth and face index); texture only for the winners.
  own(&out->depth, H, W, CV_32F);
  own(&out->image, H, W, CV_8UC3);
  own(&index_, H, W, CV_32S);
  cv::Mat& depth = out->depth;
  cv::Mat& index = index_;
  depth.setTo(std::numeric_limits<float>::infinity());
  index.setTo(-1);
  std::vector<CameraFace> faces;
  for (const auto* set : face_sets)
    for (const Face& f : *set) {
      CameraFace c;
      const Eigen::Vector3d o = camera_from_world * f.origin;
      c.u = R * f.u;
      c.v = R * f.v;
      c.n = c.u.cross(c.v);
      c.d = c.n.dot(o);
      if (std::fabs(c.d) < 1e-9) continue;  // seen edge-on
      c.ou = o.dot(c.u);
      c.ov = o.dot(c.v);
      const Eigen::Vector3d corners[4] = {o, o + f.width * c.u, o + f.width * c.u + f.height * c.v, o + f.height * c.v};
      Eigen::Vector3d clipped[8];
      const int n = clip_near(corners, 4, near, clipped);
      if (n < 3) continue;
      double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
      for (int i = 0; i < n; ++i) {
        const double px = fx * clipped[i].x() / clipped[i].z() + cx, py = fy * clipped[i].y() / clipped[i].z() + cy;
        x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
      }
      const int ix0 = std::max(0, static_cast<int>(std::floor(x0))), ix1 = std::min(W - 1, static_cast<int>(std::ceil(x1)));
      const int iy0 = std::max(0, static_cast<int>(std::floor(y0))), iy1 = std::min(H - 1, static_cast<int>(std::ceil(y1)));
      if (ix0 > ix1 || iy0 > iy1) continue;
      c.face = &f;
      c.look = texture_.look(f.material, f.surface, shade_of(f));
      const int id = static_cast<int>(faces.size());
      faces.push_back(c);
      // Along a row, n . r, u . r and v . r change linearly with the column (r = ray through
      // the pixel centre with z = 1): Z = d / (n . r), s = Z (u . r) - o . u.
      const double ax = 1.0 / fx;
      const double w = f.width, h = f.height;
      for (int y = iy0; y <= iy1; ++y) {
        const double ry = (y - cy) / fy;
        const double rx0 = (ix0 - cx) / fx;
        double den = c.n.x() * rx0 + c.n.y() * ry + c.n.z();
        double ru = c.u.x() * rx0 + c.u.y() * ry + c.u.z();
        double rv = c.v.x() * rx0 + c.v.y() * ry + c.v.z();
        const double dden = c.n.x() * ax, dru = c.u.x() * ax, drv = c.v.x() * ax;
        float* zrow = depth.ptr<float>(y);
        int* irow = index.ptr<int>(y);
        for (int x = ix0; x <= ix1; ++x, den += dden, ru += dru, rv += drv) {
          if (den == 0.0) continue;
          const double Z = c.d / den;
          if (Z < near || Z >= zrow[x]) continue;
          const double s = Z * ru - c.ou, t = Z * rv - c.ov;
          if (s < 0.0 || s > w || t < 0.0 || t > h) continue;
          zrow[x] = static_cast<float>(Z);
          irow[x] = id;
        }
      }
    }

  // Pass 2: colour every pixel from its face's texture at the point it shows.
  for (int y = 0; y < H; ++y) {
    const double ry = (y - cy) / fy;
    float* zrow = depth.ptr<float>(y);
    const int* irow = index.ptr<int>(y);
    cv::Vec3b* prow = out->image.ptr<cv::Vec3b>(y);
    for (int x = 0; x < W; ++x) {
      if (irow[x] < 0) {
        prow[x] = cv::Vec3b(0, 0, 0);
        zrow[x] = 0.0f;
        continue;
      }
      const CameraFace& c = faces[static_cast<size_t>(irow[x])];
      const double rx = (x - cx) / fx;
      const double Z = zrow[x];
      const double s = Z * (c.u.x() * rx + c.u.y() * ry + c.u.z()) - c.ou;
      const double t = Z * (c.v.x() * rx + c.v.y() * ry + c.v.z()) - c.ov;
      prow[x] = texture_.colour(c.look, static_cast<float>(s + c.face->s_offset), static_cast<float>(t));
    }
  }
}

}  // namespace rgnav::sim
