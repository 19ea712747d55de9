// The simulated stereo head against geometry worked out by hand: where a wall, a table top, a
// poster and a door appear, at what depth, with what disparity between the two images.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

#include "config/config.h"
#include "drivers/stereo/stereo_calibration.h"
#include "sim/stereo_renderer.h"
#include "sim/world_yaml.h"

namespace rgnav::sim {
namespace {

const std::string kSource = RGNAV_SOURCE_DIR;

stereo::StereoCalibration rig() { return stereo::load_stereo_calibration(kSource + "/config/stereo/sim_b21r_head.yml"); }

World parse(const std::string& yaml) { return parse_world_yaml(config::Config::parse(yaml, "test_world.yaml"), "."); }

// A wall across x = 5 from y = -1 to 1, 2.5 m high; the robot at the origin looking along +x.
const char* kWallAhead = "walls:\n  - {a: [5, -1], b: [5, 1], height: 2.5}\n";

// The sim rig: left camera 0.09 m ahead of the base, 0.06 m left, 1.25 m up; f = 500, c = (319.5, 239.5).
constexpr double kCamX = 0.09, kCamY = 0.06, kCamZ = 1.25, kF = 500, kCx = 319.5, kCy = 239.5;

TEST(StereoRenderer, WallAtKnownDistanceLandsOnTheRightPixels)
{
  const StereoRenderer r(parse(kWallAhead), rig(), {0.0, 1, 0.05});
  const StereoRender out = r.render(HeadView{});
  const double Z = 5 - kCamX;
  const cv::Mat& depth = out.left.depth;
  ASSERT_EQ(depth.size(), cv::Size(640, 480));
  EXPECT_NEAR(depth.at<float>(240, 320), Z, 1e-3);
  // Columns: y = 1 at u = cx - f (1 - 0.06) / Z = 223.8, y = -1 at cx + f (1 + 0.06) / Z = 427.4.
  const double u_left = kCx - kF * (1 - kCamY) / Z, u_right = kCx + kF * (1 + kCamY) / Z;
  EXPECT_NEAR(depth.at<float>(240, static_cast<int>(std::ceil(u_left))), Z, 1e-3);
  EXPECT_NEAR(depth.at<float>(240, static_cast<int>(std::floor(u_right))), Z, 1e-3);
  EXPECT_GT(std::fabs(depth.at<float>(240, static_cast<int>(std::floor(u_left)) - 1) - Z), 0.5);
  EXPECT_GT(std::fabs(depth.at<float>(240, static_cast<int>(std::ceil(u_right)) + 1) - Z), 0.5);
  // Rows: top edge z = 2.5 at v = cy - f (2.5 - 1.25) / Z = 112.2; the floor meets it at 366.8.
  const double v_top = kCy - kF * (2.5 - kCamZ) / Z, v_floor = kCy + kF * kCamZ / Z;
  EXPECT_NEAR(depth.at<float>(static_cast<int>(std::ceil(v_top)), 320), Z, 1e-3);
  EXPECT_LT(depth.at<float>(static_cast<int>(std::floor(v_top)) - 1, 320), Z - 0.02);  // the ceiling before it
  EXPECT_NEAR(depth.at<float>(static_cast<int>(std::floor(v_floor)), 320), Z, 1e-3);
  EXPECT_LT(depth.at<float>(static_cast<int>(std::ceil(v_floor)) + 1, 320), Z - 0.01);  // the floor before it
  // Depth is along the optical axis: the same Z across the wall.
  EXPECT_NEAR(depth.at<float>(150, 250), Z, 1e-3);
}

// A calibration with distortion: the image is the ideal one remapped through OpenCV's model, so
// a wall's edge lands where cv::projectPoints puts it, not where the pinhole would.
TEST(StereoRenderer, DistortionFollowsOpenCVsModel)
{
  stereo::StereoCalibration c = rig();
  c.D1 = (cv::Mat_<double>(1, 5) << -0.25, 0.05, 0, 0, 0);
  c.D2 = c.D1.clone();
  const StereoRenderer r(parse("walls:\n  - {a: [5, -3], b: [5, 2.5], height: 2.5}\n"), c, {0.0, 1, 0.05});
  const cv::Mat depth = r.render(HeadView{}).left.depth;
  // The wall's end y = 2.5 at camera height, in the left camera frame: x = -(2.5 - 0.06), z = 4.91.
  std::vector<cv::Point2f> edge;
  cv::projectPoints(std::vector<cv::Point3f>{{static_cast<float>(-(2.5 - kCamY)), 0.0f, static_cast<float>(5 - kCamX)}},
                    cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), c.M1, c.D1, edge);
  const double pinhole = kCx - kF * (2.5 - kCamY) / (5 - kCamX);
  ASSERT_GT(edge[0].x - pinhole, 10.0) << "barrel distortion pulls the edge inward";
  const int row = static_cast<int>(std::lround(kCy));
  EXPECT_GT(depth.at<float>(row, static_cast<int>(std::ceil(edge[0].x)) + 1), 4.0f);   // the wall (> 4 m: not the far-away nothing)
  EXPECT_EQ(depth.at<float>(row, static_cast<int>(std::floor(edge[0].x)) - 2), 0.0f);  // beyond its end: nothing at the horizon
  EXPECT_EQ(depth.at<float>(row, static_cast<int>(std::ceil(pinhole)) + 2), 0.0f);
}

// Block matching along the row finds the disparity f B / Z (B = 0.12 m) within a pixel.
TEST(StereoRenderer, DisparityOfTheRightImageIsFocalTimesBaselineOverDepth)
{
  const StereoRenderer r(parse(kWallAhead), rig());  // with the default image noise
  const StereoRender out = r.render(HeadView{});
  cv::Mat left, right;
  cv::cvtColor(out.left.image, left, cv::COLOR_BGR2GRAY);
  cv::cvtColor(out.right.image, right, cv::COLOR_BGR2GRAY);
  left.convertTo(left, CV_32F);
  right.convertTo(right, CV_32F);
  const double expected = kF * 0.12 / (5 - kCamX);  // 12.2 px
  for (const cv::Point at : {cv::Point(320, 240), cv::Point(300, 180), cv::Point(360, 300)}) {
    const cv::Rect patch(at.x - 10, at.y - 10, 21, 21);
    double best = 1e300;
    int best_d = -1;
    for (int d = 0; d <= 40; ++d) {
      const double ssd = cv::norm(left(patch), right(patch - cv::Point(d, 0)), cv::NORM_L2SQR);
      if (ssd < best) best = ssd, best_d = d;
    }
    EXPECT_NEAR(best_d, expected, 1.0) << "at " << at;
  }
}

TEST(StereoRenderer, DeterministicWithASeed)
{
  const World world = parse(std::string(kWallAhead) + "texture_seed: 7\n");
  const StereoRenderer a(world, rig()), b(world, rig());
  HeadView view;
  view.frame = 3;
  const auto ra = a.render(view), rb = b.render(view);
  EXPECT_EQ(cv::norm(ra.left.image, rb.left.image, cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(ra.right.image, rb.right.image, cv::NORM_INF), 0);
  // Another frame: other image noise, same scene.
  view.frame = 4;
  const auto rc = a.render(view);
  EXPECT_GT(cv::norm(ra.left.image, rc.left.image, cv::NORM_L1), 0);
  EXPECT_EQ(cv::norm(ra.left.depth, rc.left.depth, cv::NORM_INF), 0);
  // Another texture seed: other surfaces.
  const StereoRenderer d(parse(std::string(kWallAhead) + "texture_seed: 8\n"), rig(), {0.0, 1, 0.05});
  const StereoRenderer e(world, rig(), {0.0, 1, 0.05});
  EXPECT_GT(cv::norm(d.render(view).left.image, e.render(view).left.image, cv::NORM_L1) / (640 * 480), 5.0);
}

// A table ahead: the camera, tilted down, sees its top at 0.72 m over the floor it hides.
TEST(StereoRenderer, TableTopAppearsAtItsHeight)
{
  const World world = parse(std::string(kWallAhead) +
                            "tables:\n  - {name: desk, center: [2, 0], size: [1.2, 0.8], height: 0.72}\n");
  const StereoRenderer r(world, rig(), {0.0, 1, 0.05});
  HeadView view;
  view.tilt = -0.4;
  const StereoRender out = r.render(view);
  const Eigen::Isometry3d camera_from_world = r.world_from_left_camera(view).inverse();
  auto project = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d c = camera_from_world * p;
    return std::make_pair(cv::Point(static_cast<int>(std::lround(kF * c.x() / c.z() + kCx)),
                                    static_cast<int>(std::lround(kF * c.y() / c.z() + kCy))),
                          c.z());
  };
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(2, 0, 0.72), Eigen::Vector3d(1.7, 0.2, 0.72)}) {
    const auto [px, z] = project(p);
    ASSERT_TRUE(cv::Rect(0, 0, 640, 480).contains(px));
    EXPECT_NEAR(out.left.depth.at<float>(px), z, 0.01) << "top at " << p.transpose();
    // The floor behind it (x = 3.4: the sight line crosses the top's height over the table) is
    // hidden: the pixel shows something nearer than the floor point.
    const auto [floor_px, floor_z] = project(Eigen::Vector3d(3.4, p.y(), 0));
    ASSERT_TRUE(cv::Rect(0, 0, 640, 480).contains(floor_px));
    EXPECT_LT(out.left.depth.at<float>(floor_px), floor_z - 0.1);
  }
  // Without the table the same pixel sees the floor.
  const StereoRenderer bare(parse(kWallAhead), rig(), {0.0, 1, 0.05});
  const auto [px, z] = project(Eigen::Vector3d(2, 0, 0.72));
  const float floor_depth = bare.render(view).left.depth.at<float>(px);
  EXPECT_GT(floor_depth, z + 0.3);
}

TEST(StereoRenderer, PostersAndClosedDoorsAreDrawnOpenDoorsDoNotBlock)
{
  const World world = parse(
      "walls:\n  - {a: [5, -3], b: [5, -0.5], height: 2.5}\n  - {a: [5, 0.5], b: [5, 3], height: 2.5}\n"
      "  - {a: [8, -3], b: [8, 3], height: 2.5}\n"
      "doors:\n  - {name: d, hinge: [5, -0.5], latch: [5, 0.5], height: 2.1, open: false}\n"
      "wall_objects:\n  - {name: board, kind: whiteboard, a: [4.99, 1.2], b: [4.99, 2.4], z_min: 0.9, z_max: 1.9}\n");
  ASSERT_EQ(world.wall_objects.size(), 1u);
  const StereoRenderer r(world, rig(), {0.0, 1, 0.05});
  HeadView view;
  view.door_open = {0};
  const StereoRender closed = r.render(view);
  // The closed leaf (4 cm thick, centred on the wall line) at x = 4.98.
  EXPECT_NEAR(closed.left.depth.at<float>(300, 320), 4.98 - kCamX, 1e-3);
  view.door_open = {1};
  const StereoRender open = r.render(view);
  EXPECT_NEAR(open.left.depth.at<float>(300, 320), 8 - kCamX, 1e-3);  // through the doorway
  // The whiteboard: at x = 4.99, left of the door (y 1.2..2.4: columns cx - f (y - 0.06) / Z).
  const double Z = 4.99 - kCamX;
  const int u = static_cast<int>(kCx - kF * (1.8 - kCamY) / Z), v = static_cast<int>(kCy - kF * (1.4 - kCamZ) / Z);
  EXPECT_NEAR(open.left.depth.at<float>(v, u), Z, 1e-3);
  const cv::Vec3b board = open.left.image.at<cv::Vec3b>(v, u);
  EXPECT_GT(board[0] + board[1] + board[2], 3 * 170) << "a whiteboard is bright";
  // Above the door the wall goes on to the ceiling.
  EXPECT_NEAR(open.left.depth.at<float>(static_cast<int>(kCy - kF * (2.35 - kCamZ) / (5 - kCamX)), 320), 5 - kCamX, 0.03);
}

// Every shipped world loads and renders with the defaults (no wall objects, texture seed 1):
// floor, walls and ceiling fill the view from the start pose.
TEST(StereoRenderer, ShippedWorldsRender)
{
  for (const char* name : {"office", "hallways_2m_uncluttered", "hallways_3m_strongly_cluttered"}) {
    SCOPED_TRACE(name);
    const World world = load_world(kSource + "/config/worlds/" + name + ".yaml");
    const StereoRenderer r(world, rig());
    HeadView view;
    view.robot = world.start;
    for (const auto& p : world.people) view.people.push_back({p.path.front(), p.radius});
    const StereoRender out = r.render(view);
    EXPECT_GT(cv::countNonZero(out.left.depth > 0), 0.99 * 640 * 480);
    EXPECT_GT(cv::countNonZero(out.right.depth > 0), 0.99 * 640 * 480);
    cv::Mat grey;
    cv::cvtColor(out.left.image, grey, cv::COLOR_BGR2GRAY);
    cv::Scalar mean, stddev;
    cv::meanStdDev(grey, mean, stddev);
    EXPECT_GT(stddev[0], 10.0) << "texture";
  }
}

TEST(WallObjects, LoadedCheckedAndWrittenBack)
{
  const World w = parse(std::string(kWallAhead) +
                        "wall_objects:\n  - {name: p, a: [4.99, -0.5], b: [4.99, 0.5]}\n"
                        "  - {kind: whiteboard, a: [4.99, 0.6], b: [4.99, 0.9], z_min: 0.8, z_max: 2}\n");
  ASSERT_EQ(w.wall_objects.size(), 2u);
  EXPECT_EQ(w.wall_objects[0].kind, WallObject::Kind::kPoster);
  EXPECT_DOUBLE_EQ(w.wall_objects[0].z_min, 1.0);
  EXPECT_EQ(w.wall_objects[1].kind, WallObject::Kind::kWhiteboard);
  EXPECT_EQ(w.wall_objects[1].name, "wall_object_1");
  const World back = parse(world_to_yaml(w));
  ASSERT_EQ(back.wall_objects.size(), 2u);
  EXPECT_DOUBLE_EQ(back.wall_objects[1].z_max, 2.0);
  EXPECT_EQ(back.wall_objects[1].kind, WallObject::Kind::kWhiteboard);
  for (const char* bad : {"  - {a: [1, 1], b: [1, 1.01]}\n", "  - {a: [1, 1], b: [1, 2], z_min: 1.5, z_max: 1.5}\n",
                          "  - {a: [1, 1], b: [1, 2], kind: mirror}\n"})
    EXPECT_THROW(parse(std::string(kWallAhead) + "wall_objects:\n" + bad), config::ConfigError) << bad;
}

}  // namespace
}  // namespace rgnav::sim
