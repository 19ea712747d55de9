#include <gtest/gtest.h>
#include <zlib.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "importers/carmen_parser.h"
#include "importers/lcm_log_io.h"
#include "importers/mines_parser.h"
#include "importers/odometry_alignment.h"
#include "importers/reference_matching.h"
#include "bad_files.h"

namespace imp = rgnav::importers;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir()
{
  const fs::path d = fs::temp_directory_path() / ("rgnav_importers_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

std::string flaser(int n, double r, double x, double y, double th, double t)
{
  std::string s = "FLASER " + std::to_string(n);
  for (int i = 0; i < n; ++i) s += " " + std::to_string(r + 0.01 * i);
  char tail[200];
  std::snprintf(tail, sizeof tail, " %f %f %f %f %f %f %f host %f", x, y, th, x, y, th, t, t);
  return s + tail;
}

void write_gz(const fs::path& p, const std::string& text)
{
  gzFile f = gzopen(p.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  gzwrite(f, text.data(), static_cast<unsigned>(text.size()));
  gzclose(f);
}

}  // namespace

TEST(CarmenParser, ParsesFlaserOdomRobotlaserAndSkipsOtherMessages)
{
  imp::ImportedLog log;
  std::string why;
  imp::CarmenOptions o;
  EXPECT_TRUE(imp::parse_carmen_line("# comment", o, &log, &why));
  EXPECT_TRUE(imp::parse_carmen_line("PARAM robot_frontlaser_offset 0.0 nohost 0", o, &log, &why));
  EXPECT_TRUE(imp::parse_carmen_line("ODOM 1.5 2.5 0.1 0 0 0 10.25 host 10.25", o, &log, &why)) << why;
  EXPECT_TRUE(imp::parse_carmen_line(flaser(180, 1.0, 1.0, 2.0, 0.5, 10.5), o, &log, &why)) << why;
  std::string rl = "ROBOTLASER1 0 -1.570796 3.141593 0.017453 80.0 0.01 0 3 1.0 2.0 81.9 0 "
                   "0.1 0.2 0.3 0.4 0.5 0.6 0 0 0 0 0 11.0 b21 11.1";
  EXPECT_TRUE(imp::parse_carmen_line(rl, o, &log, &why)) << why;
  ASSERT_EQ(log.scans.size(), 2u);
  ASSERT_EQ(log.odometry.size(), 3u);
  EXPECT_EQ(log.odometry[0].utime, 10'250'000);
  EXPECT_DOUBLE_EQ(log.odometry[0].x, 1.5);
  EXPECT_EQ(log.scans[0].ranges.size(), 180u);
  EXPECT_NEAR(log.scans[0].angle_min, -M_PI / 2, 1e-6);
  EXPECT_NEAR(log.scans[0].angle_increment, M_PI / 180, 1e-6);
  EXPECT_EQ(log.scans[0].utime, 10'500'000);
  EXPECT_EQ(log.scans[1].ranges.size(), 3u);
  EXPECT_FLOAT_EQ(log.scans[1].range_max, 80.f);
  EXPECT_DOUBLE_EQ(log.odometry[2].x, 0.4);  // robot pose, not the laser pose
  EXPECT_TRUE(log.reference.empty());
}

TEST(CarmenParser, FovInclusiveBeamSpacingForMrptDecodedLogs)
{
  // MRPT's CObservation2DRangeScan spreads n beams over the aperture inclusive of both ends.
  imp::ImportedLog log;
  imp::CarmenOptions o;
  o.fov_inclusive = true;
  std::string why;
  ASSERT_TRUE(imp::parse_carmen_line(flaser(180, 1.0, 0.0, 0.0, 0.0, 1.0), o, &log, &why)) << why;
  ASSERT_EQ(log.scans.size(), 1u);
  EXPECT_NEAR(log.scans[0].angle_min, -M_PI / 2, 1e-6);
  EXPECT_NEAR(log.scans[0].angle_min + 179 * log.scans[0].angle_increment, M_PI / 2, 1e-5);
}

TEST(OdometryAlignment, DelayGivesEachScanThePoseOfTheScanBefore)
{
  // The Intel rawlog decoding: ODOM then FLASER (with the same pose) per scan, all at one
  // synthetic timestamp, and every pose one scan ahead. Scan k's odometry is in x = k + 1.
  imp::ImportedLog log;
  imp::CarmenOptions o;
  std::string why;
  for (int k = 0; k < 4; ++k) {
    const double x = k + 1.0;
    const std::string odom = "ODOM " + std::to_string(x) + " 0 0 0 0 0 5.0 host 5.0";
    ASSERT_TRUE(imp::parse_carmen_line(odom, o, &log, &why)) << why;
    ASSERT_TRUE(imp::parse_carmen_line(flaser(180, 1.0, x, 0.0, 0.0, 5.0), o, &log, &why)) << why;
  }
  ASSERT_EQ(log.odometry.size(), 8u);
  EXPECT_EQ(imp::delay_odometry_by_scans(&log, 1), 6u);  // the first scan's two records keep theirs
  // What a consumer reading the log in order sees at each scan: the last odometry before it.
  std::vector<double> at_scan;
  double last = -1.0;
  for (const auto& e : log.events) {
    if (e.kind == imp::LogEvent::Kind::kOdometry) last = log.odometry[e.index].x;
    if (e.kind == imp::LogEvent::Kind::kScan) at_scan.push_back(last);
  }
  EXPECT_EQ(at_scan, (std::vector<double>{1.0, 1.0, 2.0, 3.0}));
  for (const auto& p : log.odometry) EXPECT_EQ(p.utime, 5'000'000);  // timestamps kept
  EXPECT_EQ(imp::delay_odometry_by_scans(&log, 0), 0u);
}

TEST(CarmenParser, RejectsMalformedLinesWithReasons)
{
  imp::ImportedLog log;
  imp::CarmenOptions o;
  std::string why;
  EXPECT_FALSE(imp::parse_carmen_line("FLASER 180 1.0 2.0", o, &log, &why));
  EXPECT_NE(why.find("expected"), std::string::npos);
  EXPECT_FALSE(imp::parse_carmen_line("ODOM 1 2 x 0 0 0 1 h 1", o, &log, &why));
  EXPECT_NE(why.find("not a number"), std::string::npos);
  EXPECT_FALSE(imp::parse_carmen_line("FLASER -3", o, &log, &why));
  auto bad = flaser(4, 1.0, 0, 0, 0, 1);
  bad.replace(bad.find("1.01"), 4, "nan ");
  EXPECT_FALSE(imp::parse_carmen_line(bad, o, &log, &why));
  EXPECT_TRUE(log.scans.empty());
  EXPECT_TRUE(log.odometry.empty());
}

TEST(CarmenParser, ReportsBadLinesByNumberAndKeepsTheRest)
{
  const auto dir = temp_dir();
  const auto p = dir / "bad.log";
  std::ofstream(p) << flaser(10, 1.0, 0, 0, 0, 1) << "\n"
                   << "FLASER 10 1 2 3\n"
                   << flaser(10, 1.0, 0.1, 0, 0, 2) << "\n"
                   << "ODOM 1 2 3\n";
  const auto log = imp::read_carmen(p.string());
  EXPECT_EQ(log.scans.size(), 2u);
  ASSERT_EQ(log.issues.size(), 2u);
  EXPECT_EQ(log.issues[0].line, 2);
  EXPECT_EQ(log.issues[1].line, 4);
  EXPECT_FALSE(log.truncated);
}

TEST(CarmenParser, TruncatedGzipImportsTheValidPrefix)
{
  const auto dir = temp_dir();
  std::string text;
  for (int i = 0; i < 400; ++i) text += flaser(180, 1.0 + i * 0.001, i * 0.1, 0, 0, i) + "\n";
  const auto full = dir / "full.log.gz";
  write_gz(full, text);
  const auto whole = imp::read_carmen(full.string());
  EXPECT_EQ(whole.scans.size(), 400u);
  EXPECT_FALSE(whole.truncated);

  const auto cut = dir / "cut.log.gz";
  fs::copy_file(full, cut, fs::copy_options::overwrite_existing);
  fs::resize_file(cut, fs::file_size(full) / 2);
  const auto part = imp::read_carmen(cut.string());
  EXPECT_TRUE(part.truncated);
  EXPECT_GT(part.scans.size(), 20u);
  EXPECT_LT(part.scans.size(), 400u);
  ASSERT_FALSE(part.issues.empty());
  EXPECT_NE(part.issues.back().what.find("truncated"), std::string::npos);
  // Every imported scan is complete and equal to the original.
  for (size_t i = 0; i < part.scans.size(); ++i) {
    ASSERT_EQ(part.scans[i].ranges.size(), 180u);
    EXPECT_EQ(part.scans[i].ranges, whole.scans[i].ranges);
  }
}

TEST(LcmLog, RoundTripKeepsScansOdometryReferencesAndOrder)
{
  imp::ImportedLog log;
  imp::CarmenOptions o;
  o.flaser_pose_is_reference = true;
  std::string why;
  ASSERT_TRUE(imp::parse_carmen_line("ODOM 0 0 0 0 0 0 0.5 h 0.5", o, &log, &why));
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(imp::parse_carmen_line(flaser(180, 2.0, i * 0.2, 0.1, 0.05 * i, 1.0 + i), o, &log, &why));
  const auto path = (temp_dir() / "rt.lcmlog").string();
  const auto sum = imp::write_lcm_log(log, path);
  EXPECT_EQ(sum.scans, 5u);
  EXPECT_EQ(sum.odometry, 6u);
  EXPECT_EQ(sum.reference, 5u);
  const auto back = imp::read_lcm_log(path);
  EXPECT_TRUE(back.issues.empty());
  ASSERT_EQ(back.scans.size(), 5u);
  ASSERT_EQ(back.odometry.size(), 6u);
  ASSERT_EQ(back.reference.size(), 5u);
  ASSERT_EQ(back.events.size(), log.events.size());
  for (size_t i = 0; i < log.events.size(); ++i) EXPECT_EQ(back.events[i].kind, log.events[i].kind);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(back.scans[i].scan_id, static_cast<int64_t>(i + 1));
    EXPECT_EQ(back.scans[i].utime, log.scans[i].utime);
    EXPECT_EQ(back.scans[i].ranges, log.scans[i].ranges);
    EXPECT_EQ(back.reference[i].seq, static_cast<int64_t>(i + 1));  // the scan it belongs to
    EXPECT_NEAR(back.reference[i].x, i * 0.2, 1e-9);
  }
  EXPECT_NEAR(back.odometry[5].theta, 0.2, 1e-9);
}

TEST(LcmLog, TruncatedLogKeepsCompleteEvents)
{
  imp::ImportedLog log;
  std::string why;
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(imp::parse_carmen_line(flaser(180, 2.0, i * 0.2, 0, 0, 1.0 + i), {}, &log, &why));
  const auto path = temp_dir() / "cut.lcmlog";
  imp::write_lcm_log(log, path.string());
  fs::resize_file(path, fs::file_size(path) - 100);
  const auto back = imp::read_lcm_log(path.string());
  EXPECT_TRUE(back.truncated);
  EXPECT_EQ(back.scans.size(), 49u);
}

// Issue 35: a file that is no LCM log is refused naming it (it used to read as an empty log
// with a "truncated" warning); a log cut off mid-event keeps what came before, with a warning.
TEST(LcmLog, RandomBytesEmptyAndCutOffLogs)
{
  imp::ImportedLog log;
  std::string why;
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(imp::parse_carmen_line(flaser(180, 2.0, i * 0.2, 0, 0, 1.0 + i), {}, &log, &why));
  const auto dir = temp_dir();
  const auto valid = (dir / "valid.lcmlog").string();
  imp::write_lcm_log(log, valid);
  std::ifstream in(valid, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto bad = rgnav::testing::write_bad_files(dir.string(), "log.lcmlog", bytes, bytes.size() / 2 + 7);
  for (const auto& f : bad) {
    SCOPED_TRACE(f.kind);
    if (f.kind == "truncated") {
      const auto part = imp::read_lcm_log(f.path);
      EXPECT_TRUE(part.truncated);
      EXPECT_GT(part.scans.size(), 5u);
      EXPECT_LT(part.scans.size(), 15u);
      ASSERT_FALSE(part.issues.empty());
      EXPECT_NE(part.issues.back().what.find("truncated"), std::string::npos);
      continue;
    }
    try {
      imp::read_lcm_log(f.path);
      ADD_FAILURE() << f.path << " was read as an LCM log";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(f.path), std::string::npos) << e.what();
    }
  }
  // Cut inside its first event: no complete event, nothing valid.
  const auto first = (dir / "first.lcmlog").string();
  rgnav::testing::write_bytes(first, bytes.substr(0, 40));
  EXPECT_THROW(imp::read_lcm_log(first), std::runtime_error);
  // Junk in front of a valid log: lcm's reader would skip to the first sync word in silence.
  const auto prefixed = (dir / "prefixed.lcmlog").string();
  rgnav::testing::write_bytes(prefixed, "not a log" + bytes);
  EXPECT_THROW(imp::read_lcm_log(prefixed), std::runtime_error);
  // Junk between two events: what came before is read, and the damage is reported (LCM 1.3's
  // reader stops there; a reader that resynchronises goes on, and the skipped bytes are reported).
  const auto middle = (dir / "middle.lcmlog").string();
  const size_t second_half = bytes.find("\xed\xa1\xda\x01", bytes.size() / 2);
  ASSERT_NE(second_half, std::string::npos);
  rgnav::testing::write_bytes(middle, bytes.substr(0, second_half) + "junk" + bytes.substr(second_half));
  const auto mended = imp::read_lcm_log(middle);
  EXPECT_GE(mended.scans.size(), 9u);
  ASSERT_EQ(mended.issues.size(), 1u);
  const std::string what = mended.issues[0].what;
  EXPECT_TRUE(mended.truncated ? what.find("damaged or truncated") != std::string::npos
                               : what.find("4 damaged bytes skipped") != std::string::npos)
      << what;
}

// Issue 35: `./rgnav import` on random bytes or an empty file (CARMEN or Mines) exits non-zero
// naming it and writes no LCM log; a CARMEN log cut off mid-line is imported up to the damage,
// with the bad line named.
TEST(ImportTool, RandomBytesAndEmptyFilesAreRefusedACutOffLogIsImportedToTheDamage)
{
  rgnav::testing::TempDir dir("import_bad");
  std::string carmen, mines;
  for (int i = 0; i < 20; ++i) {
    carmen += flaser(180, 1.0 + i * 0.01, i * 0.1, 0, 0, i + 1) + "\n";
    mines += std::to_string(1000000 + i * 100000) + " 7 " + std::to_string(100 * i) + " " + std::to_string(100 * i);
    for (int k = 0; k < 20; ++k) mines += " 0";
    for (int k = 0; k < 683; ++k) mines += " " + std::to_string(1000 + k);
    mines += "\n";
  }
  for (const auto& [name, valid] : {std::pair<std::string, std::string>{"in.log", carmen}, {"in.dat", mines}}) {
    size_t cut = 0;
    for (int line = 0; line < 10; ++line) cut = valid.find('\n', cut) + 1;
    for (const auto& f : rgnav::testing::write_bad_files(dir.path(), name, valid, cut + 30)) {
      SCOPED_TRACE(f.kind + " " + f.path);
      const std::string out = f.path + ".lcmlog";
      const auto r = rgnav::testing::run_tool({RGNAV_IMPORT_BIN, f.path, out}, dir.path());
      if (f.kind == "truncated") {
        EXPECT_TRUE(r.status.clean()) << r.err;
        EXPECT_NE(r.err.find(f.path + ":11: "), std::string::npos) << r.err;   // the cut line, named
        EXPECT_EQ(imp::read_lcm_log(out).scans.size(), 10u);
        continue;
      }
      EXPECT_TRUE(r.status.exited && r.status.code != 0) << r.status.describe();
      EXPECT_NE(r.err.find(f.path), std::string::npos) << r.err;
      EXPECT_FALSE(fs::exists(out));
    }
  }
  // A reference log with nothing in it is refused too, before anything is written.
  rgnav::testing::write_bytes(dir.file("good.log"), carmen);
  rgnav::testing::write_bytes(dir.file("empty_ref.log"), rgnav::testing::random_bytes(2000));
  const auto r = rgnav::testing::run_tool(
      {RGNAV_IMPORT_BIN, dir.file("good.log"), dir.file("ref.lcmlog"), "--reference-from", dir.file("empty_ref.log")}, dir.path());
  EXPECT_TRUE(r.status.exited && r.status.code != 0) << r.status.describe();
  EXPECT_NE(r.err.find(dir.file("empty_ref.log")), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.file("ref.lcmlog")));
}

TEST(MinesParser, IntegratesWheelTicksAndMarksMarginBeams)
{
  const auto p = temp_dir() / "exp.dat";
  {
    std::ofstream f(p);
    // Straight: both wheels +1000 ticks = half a turn = pi * 0.077 m. Then a turn in place.
    const int64_t ticks[3][2] = {{0, 0}, {1000, 1000}, {500, 1500}};
    for (int k = 0; k < 3; ++k) {
      f << 1000000 + k * 100000 << " 7 " << ticks[k][0] << " " << ticks[k][1];
      for (int i = 0; i < 20; ++i) f << " 0";
      for (int i = 0; i < 683; ++i) f << " " << 1000 + i;
      f << "\n";
    }
    f << "123 7 1 2 3\n";  // malformed: too short
  }
  const auto log = imp::read_mines(p.string());
  ASSERT_EQ(log.scans.size(), 3u);
  ASSERT_EQ(log.issues.size(), 1u);
  EXPECT_EQ(log.issues[0].line, 4);
  EXPECT_EQ(log.scans[0].ranges.size(), 683u);
  EXPECT_EQ(log.scans[0].ranges[0], 0.f);     // margin
  EXPECT_EQ(log.scans[0].ranges[682], 0.f);
  EXPECT_FLOAT_EQ(log.scans[0].ranges[100], 1.1f);
  EXPECT_NEAR(log.scans[0].angle_min, -341 * 2 * M_PI / 1024, 1e-6);
  EXPECT_NEAR(log.odometry[1].x, M_PI * 0.077, 1e-9);
  EXPECT_NEAR(log.odometry[1].y, 0.0, 1e-12);
  // Turn in place: left -500, right +500 ticks: dtheta = (dr - dl) / axle.
  const double arc = 500.0 * 2 * M_PI * 0.077 / 2000.0;
  EXPECT_NEAR(log.odometry[2].theta, 2 * arc / 0.33, 1e-9);
  EXPECT_NEAR(log.odometry[2].x, M_PI * 0.077, 1e-9);
}

TEST(ReferenceMatching, IdenticalScansTakeTheCorrectedPose)
{
  imp::ImportedLog raw, corrected;
  imp::CarmenOptions ref;
  ref.flaser_pose_is_reference = true;
  std::string why;
  for (int i = 0; i < 6; ++i) ASSERT_TRUE(imp::parse_carmen_line(flaser(180, 1.0 + 0.3 * i, i, 0, 0, i), {}, &raw, &why));
  // Corrected log: scans 1 and 4 of the raw log (re-quantised), at other poses and times.
  ASSERT_TRUE(imp::parse_carmen_line(flaser(180, 1.3, 10, 11, 0.5, 100), ref, &corrected, &why));
  ASSERT_TRUE(imp::parse_carmen_line(flaser(180, 2.2, 20, 21, 0.7, 200), ref, &corrected, &why));
  ASSERT_TRUE(imp::parse_carmen_line(flaser(180, 9.0, 30, 31, 0.9, 300), ref, &corrected, &why));  // no match
  EXPECT_EQ(imp::add_reference_from_corrected(corrected, &raw), 2u);
  ASSERT_EQ(raw.reference.size(), 2u);
  EXPECT_EQ(raw.reference[0].utime, raw.scans[1].utime);
  EXPECT_DOUBLE_EQ(raw.reference[0].x, 10.0);
  EXPECT_EQ(raw.reference[1].utime, raw.scans[4].utime);
  EXPECT_DOUBLE_EQ(raw.reference[1].y, 21.0);
  const auto path = (temp_dir() / "ref.lcmlog").string();
  imp::write_lcm_log(raw, path);
  const auto back = imp::read_lcm_log(path);
  ASSERT_EQ(back.reference.size(), 2u);
  EXPECT_EQ(back.reference[0].seq, 2);
  EXPECT_EQ(back.reference[1].seq, 5);
}
