// rgnav_import: recorded laser logs → LCM log files (LASER_FRONT, ODOMETRY, REFERENCE_POSE).
//   rgnav_import IN OUT.lcmlog [--format auto|carmen|mines] [--reference] [--reference-from CORRECTED]
//   [--fov-inclusive] [--max-range M] [--odometry-delay-scans N]
// Malformed lines are reported with their line numbers and skipped; a truncated input imports
// what is valid. Exit 0 when something was imported, 1 when nothing could be, 2 on bad usage.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <iostream>

#include "importers/carmen_parser.h"
#include "importers/lcm_log_io.h"
#include "importers/mines_parser.h"
#include "importers/odometry_alignment.h"
#include "importers/reference_matching.h"

namespace imp = rgnav::importers;

namespace {

std::string detect_format(const std::string& path)
{
  const std::string name = std::filesystem::path(path).filename().string();
  if (name.size() > 4 && name.substr(name.size() - 4) == ".dat") return "mines";
  return "carmen";
}

void report(const imp::ImportedLog& log, const std::string& path, size_t max_lines = 20)
{
  for (size_t i = 0; i < log.issues.size() && i < max_lines; ++i)
    std::cerr << path << ":" << log.issues[i].line << ": " << log.issues[i].what << "\n";
  if (log.issues.size() > max_lines) std::cerr << path << ": ... " << log.issues.size() - max_lines << " more\n";
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Import a CARMEN or Mines laser log into an LCM log"};
  std::string in, out, format = "auto", reference_from;
  bool reference = false, fov_inclusive = false;
  float max_range = 80.f;
  int odometry_delay_scans = 0;
  app.add_option("input", in, "CARMEN log (.log, .log.gz, .clf) or Mines .dat")->required()->check(CLI::ExistingFile);
  app.add_option("output", out, "LCM log to write")->required();
  app.add_option("--format", format, "auto, carmen or mines")->check(CLI::IsMember({"auto", "carmen", "mines"}));
  app.add_flag("--reference", reference, "the log's FLASER/ROBOTLASER1 poses are corrected: also write REFERENCE_POSE");
  app.add_option("--reference-from", reference_from, "corrected CARMEN log of the same run: reference poses for identical scans")
      ->check(CLI::ExistingFile);
  app.add_flag("--fov-inclusive", fov_inclusive,
               "FLASER beams span 180 deg inclusive (fov/(n-1)), as MRPT spreads them (not for logs that came from CARMEN)");
  app.add_option("--max-range", max_range, "range limit for FLASER/RLASER (no limit in the format) [m]");
  app.add_option("--odometry-delay-scans", odometry_delay_scans,
                 "the log pairs each scan with the odometry of N scans later: give each scan the earlier pose")
      ->check(CLI::Range(0, 100));
  CLI11_PARSE(app, argc, argv);
  if (format == "auto") format = detect_format(in);
  try {
    imp::ImportedLog log;
    if (format == "mines") {
      log = imp::read_mines(in);
    } else {
      imp::CarmenOptions o;
      o.old_laser_range_max = max_range;
      o.flaser_pose_is_reference = reference;
      o.fov_inclusive = fov_inclusive;
      log = imp::read_carmen(in, o);
    }
    report(log, in);
    if (odometry_delay_scans > 0) {
      const size_t n = imp::delay_odometry_by_scans(&log, odometry_delay_scans);
      std::cerr << in << ": odometry delayed by " << odometry_delay_scans << " scan(s), " << n << " poses changed\n";
    }
    if (!reference_from.empty()) {
      imp::CarmenOptions o;
      o.old_laser_range_max = max_range;
      o.flaser_pose_is_reference = true;
      const auto corrected = imp::read_carmen(reference_from, o);
      report(corrected, reference_from);
      if (corrected.scans.empty()) {   // no reference at all: write no log that claims one
        std::cerr << reference_from << ": no scans in the corrected log (" << corrected.issues.size() << " bad lines)\n";
        return 1;
      }
      const size_t n = imp::add_reference_from_corrected(corrected, &log);
      std::cerr << "reference poses from " << reference_from << ": " << n << " of " << corrected.scans.size()
                << " corrected scans match a raw scan\n";
    }
    if (log.scans.empty()) {
      std::cerr << in << ": no scans imported (" << log.issues.size() << " bad lines)\n";
      return 1;
    }
    const auto sum = imp::write_lcm_log(log, out);
    std::cerr << out << ": " << sum.scans << " scans, " << sum.rear_scans << " rear scans, " << sum.odometry
              << " odometry, " << sum.reference << " reference poses; " << log.issues.size() << " lines skipped"
              << (log.truncated ? " (input truncated)" : "") << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rgnav_import: " << e.what() << "\n";
    return 1;
  }
}
