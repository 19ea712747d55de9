#include "carmen_drive.h"

#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

namespace rgnav::localize_eval {

CarmenDrive::CarmenDrive(const std::string& dir, const geometry::Pose2& base_from_laser, int scan_every)
    : dir_(dir), base_from_laser_(base_from_laser), scan_every_(std::max(1, scan_every))
{
  std::filesystem::create_directories(dir);
  log_.open(dir + "/drive.carmen");
  truth_.open(dir + "/truth.txt");
  if (!log_ || !truth_) throw std::runtime_error(dir + ": cannot write the drive");
  log_ << "# rgnav localization benchmark drive: ODOM 50 Hz, FLASER (181 beams, -90..90 deg), message time [s]\n";
}

void CarmenDrive::odometry(int64_t utime, const geometry::Pose2& o, double v, double omega)
{
  const double t = static_cast<double>(utime) * 1e-6;
  log_ << fmt::format("ODOM {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} 0 {:.6f} rgnav {:.6f}\n", o.x(), o.y(), o.theta(), v, omega, t, t);
}

void CarmenDrive::scan(const sensors::LaserScan& s, const geometry::Pose2& odom, const geometry::Pose2* truth)
{
  if (scans_++ % scan_every_ != 0) return;
  const double t = static_cast<double>(s.utime) * 1e-6;
  const geometry::Pose2 laser = odom * base_from_laser_;
  std::string line = fmt::format("FLASER {}", s.ranges.size());
  for (float r : s.ranges) line += fmt::format(" {:.3f}", std::min(static_cast<double>(r), s.range_max));
  line += fmt::format(" {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} rgnav {:.6f}\n", laser.x(), laser.y(), laser.theta(),
                      odom.x(), odom.y(), odom.theta(), t, t);
  log_ << line;
  if (truth) truth_ << fmt::format("{:.6f} {:.6f} {:.6f} {:.6f}\n", t, truth->x(), truth->y(), truth->theta());
}

void CarmenDrive::start(const std::string& mode, const geometry::Pose2& p)
{
  std::ofstream f(dir_ + "/start.txt");
  f << fmt::format("{} {:.6f} {:.6f} {:.6f}\n", mode, p.x(), p.y(), p.theta());
}

}  // namespace rgnav::localize_eval
