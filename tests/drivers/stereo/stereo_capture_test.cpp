#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>

#include "bad_files.h"
#include "bus/fake_bus.h"
#include "drivers/stereo/image_encoding.h"
#include "drivers/stereo/image_folder_source.h"
#include "drivers/stereo/stereo_capture_node.h"
#include "rgnav/stereo_images_t.hpp"

namespace rgnav::stereo {
namespace {

const std::string kData = RGNAV_DATA_DIR;

TEST(ImageFolderSource, PairsTheRealChessboardSet)
{
  ImageFolderSource s({kData + "/stereo/chessboard", "left", "right", false, false});
  EXPECT_EQ(s.pairs(), 13u);
  int n = 0;
  while (auto f = s.next()) {
    EXPECT_EQ(f->left.size(), cv::Size(640, 480));
    EXPECT_EQ(f->right.size(), f->left.size());
    ++n;
  }
  EXPECT_EQ(n, 13);
  EXPECT_EQ(s.error(), "end of image sequence");
}

TEST(ImageFolderSource, TokensInsideNames)
{
  ImageFolderSource aloe({kData + "/stereo/aloe", "L.", "R.", true, true});
  ASSERT_EQ(aloe.pairs(), 1u);
  const auto f = aloe.next();
  ASSERT_TRUE(f);
  EXPECT_EQ(f->left.size(), cv::Size(1282, 1110));
  EXPECT_EQ(f->left.channels(), 1);
  EXPECT_TRUE(aloe.next());  // loops
  ImageFolderSource mrpt({kData + "/stereo/mrpt-stereo-calib", "_left", "_right", true, false});
  EXPECT_EQ(mrpt.pairs(), 4u);
}

TEST(ImageFolderSource, MissingFolderOrNoPairsRefused)
{
  EXPECT_THROW(ImageFolderSource({"/nonexistent", "left", "right", true, false}), std::runtime_error);
  EXPECT_THROW(ImageFolderSource({kData + "/stereo/aloe", "left", "right", true, false}), std::runtime_error);
}

// Issue 35: a folder whose first pair has an image of random bytes, an empty one or one cut off
// mid-content (a JPEG decoder alone fills the missing rows with grey) is refused at start-up,
// naming the file; the same file later in the sequence is a failed frame naming it.
TEST(ImageFolderSource, RandomBytesEmptyAndCutOffImagesAreRefusedNamingThem)
{
  testing::TempDir dir("stereo_bad");
  const std::string jpeg = testing::read_file(kData + "/stereo/aloe/aloeL.jpg");
  ASSERT_GT(jpeg.size(), 1000u);
  for (const auto& f : testing::write_bad_files(dir.path(), "image.jpg", jpeg)) {
    SCOPED_TRACE(f.kind);
    const std::string folder = dir.file(f.kind);
    std::filesystem::create_directories(folder);
    std::filesystem::copy_file(f.path, folder + "/a_left.jpg");
    testing::write_bytes(folder + "/a_right.jpg", jpeg);
    try {
      ImageFolderSource s({folder, "left", "right", true, false});
      ADD_FAILURE() << "a folder starting with a bad image was taken";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(folder + "/a_left.jpg"), std::string::npos) << e.what();
    }
    // After a good first pair: that frame fails, naming the file, and the sequence goes on.
    std::filesystem::rename(folder + "/a_left.jpg", folder + "/b_left.jpg");
    std::filesystem::copy_file(folder + "/a_right.jpg", folder + "/b_right.jpg");
    testing::write_bytes(folder + "/a_left.jpg", jpeg);
    ImageFolderSource s({folder, "left", "right", true, false});
    EXPECT_TRUE(s.next());
    EXPECT_FALSE(s.next());
    EXPECT_NE(s.error().find(folder + "/b_left.jpg"), std::string::npos) << s.error();
    EXPECT_TRUE(s.next());   // looped to the good pair
  }
}

TEST(CameraPairSource, MissingDeviceNamedInError)
{
  try {
    CameraPairSource cams({"/dev/video_rgnav_missing", "/dev/video_rgnav_missing2", 640, 480, 10, false});
    FAIL() << "opened a camera that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/video_rgnav_missing"), std::string::npos);
  }
}

TEST(ImageEncoding, RawIsLosslessJpegIsClose)
{
  const cv::Mat img = cv::imread(kData + "/stereo/aloe/aloeL.jpg", cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  const image_t raw = encode_image(img, 5, Encoding::kRaw, 90);
  EXPECT_EQ(raw.pixel_format, image_t::FORMAT_BGR8);
  EXPECT_EQ(raw.size, img.cols * img.rows * 3);
  const auto back = decode_image(raw);
  ASSERT_TRUE(back);
  EXPECT_EQ(cv::norm(*back, img, cv::NORM_INF), 0);

  const image_t jpg = encode_image(img, 5, Encoding::kJpeg, 90);
  EXPECT_EQ(jpg.pixel_format, image_t::FORMAT_JPEG);
  EXPECT_LT(jpg.size, raw.size / 4);
  const auto jback = decode_image(jpg);
  ASSERT_TRUE(jback);
  EXPECT_LT(cv::norm(*jback, img, cv::NORM_L1) / (img.total() * 3), 4.0);  // mean abs error < 4 grey levels
  image_t broken = jpg;
  broken.data.resize(10);
  broken.size = 10;
  EXPECT_FALSE(decode_image(broken));
}

TEST(StereoCaptureNode, PublishesValidPairsWithIncreasingFrameIds)
{
  auto b = std::make_unique<bus::FakeBus>();
  auto* bus = b.get();
  runtime::NodeOptions no;
  no.name = "stereo_capture";
  runtime::Node node(no, std::move(b));
  CaptureOptions o;
  o.encoding = Encoding::kJpeg;
  o.calibration_id = "chessboard";
  StereoCaptureNode capture(node, o, std::make_unique<ImageFolderSource>(ImageFolderOptions{kData + "/stereo/chessboard", "left", "right", false, false}));
  for (int i = 0; i < 14; ++i) capture.capture_once();
  const auto sent = bus->published_on("STEREO_IMAGES");
  ASSERT_EQ(sent.size(), 13u);
  EXPECT_EQ(capture.failures(), 1);  // the 14th: end of sequence
  stereo_images_t m;
  std::string why;
  ASSERT_TRUE(bus::decode(sent.back().data.data(), sent.back().data.size(), &m, &why)) << why;
  EXPECT_EQ(m.frame_id, 13);
  EXPECT_EQ(m.calibration_id, "chessboard");
  EXPECT_EQ(m.left.width, 640);
  EXPECT_TRUE(decode_image(m.right));
}

TEST(StereoCaptureConfig, ShippedConfigValidates)
{
  const auto cfg = config::Config::load(std::string(RGNAV_SOURCE_DIR) + "/config/stereo_capture.yaml");
  runtime::load_node_options(cfg.section("node"), "stereo_capture");
  const auto o = load_capture_options(cfg.section("capture"), cfg.section("channels"), kData,
                                      std::string(RGNAV_SOURCE_DIR) + "/config");
  EXPECT_NO_THROW(cfg.finish());
  EXPECT_NO_THROW(make_source(o));
}

}  // namespace
}  // namespace rgnav::stereo
