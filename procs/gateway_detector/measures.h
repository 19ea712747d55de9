// Measures of a VLM hypothesis against the scan (diss. 4.1.2): the general model measures W_d
// (hallway width) and W_r (rectangularity), the free-space measures per sector (On Line: the
// beams end on the sector's line; Over Line: the beams pass a line set back behind it), and
// the class weights W(GW, VLM) that make up one observation vector.
#pragma once

#include <array>
#include <string>

#include "gateway_detector/scan.h"
#include "gateway_detector/vlm.h"

namespace rgnav::gateway_detector {

// Crossing classes of 4.1.3 in observation-vector order; the last two are the counterbalance
// classes (dead end has sequences, hallway never does).
enum CrossingClass { kX = 0, kT, kLT, kRT, kLTurn, kRTurn, kDeadEnd, kHallway, kNumCrossingClasses };
constexpr int kNumSequenceClasses = 7;  // all but the hallway
const char* crossing_class_name(int c);
int crossing_class_from_name(const std::string& name);  // -1 if unknown

enum Sector { kLeftSector = 0, kFrontSector = 1, kRightSector = 2 };
// Which sectors a class expects open (Over Line FSM); the others must show a wall (On Line).
bool expects_open(int cls, int sector);

using ObservationVector = std::array<double, kNumCrossingClasses>;

struct MeasureOptions
{
  double hallway_width = 2.0;   // [m] d_hw
  double on_line_low = -0.2;    // [m] d(P_i) - d(P_i^vl) within [low, high] counts as on the line
  double on_line_high = 0.2;
  double over_line_setback = 0.25; // [m] l_par lies this far behind the sector's line
  double f_vlm = 0.5;           // weight of the general model measures
  double f_gw = 1.0;            // weight of the class-specific free-space measures
  // Clutter in front of a sector's line (a box before a wall, a person in an opening) hides
  // what the sector is: its beams end more than -on_line_low before the line. The dissertation
  // counts them against both FSMs (so clutter looks like neither wall nor opening); with this
  // set they are left out of N_Si, and both FSMs speak only for the beams that reach the line.
  bool exclude_occluded = false;
  int min_visible_beams = 3;    // fewer visible beams: both FSMs of the sector are 0
};

struct Measures
{
  double w_d = 0.0;
  double w_r = 0.0;
  std::array<double, 3> on_line{};    // per sector
  std::array<double, 3> over_line{};
  std::array<double, 3> occluded{};   // fraction of the sector's beams ending before its line
  std::array<int, 3> beams{};         // N_Si
};

// Both free-space measures of one sector in one pass over its beams.
struct SectorMeasures
{
  double on_line = 0.0;
  double over_line = 0.0;
  double occluded = 0.0;
  int beams = 0;  // valid beams between the gateway points
};
SectorMeasures sector_measures(const sensors::LaserScan& scan, const Line& line, const Vec2& a, const Vec2& b, const MeasureOptions& o);

double distance_measure(const Vlm& vlm, double hallway_width);  // W_d
double rectangularity_measure(const Vlm& vlm);                  // W_r
// On Line / Over Line FSM of the beams between gateway points a and b (bearing order free).
double on_line_fsm(const sensors::LaserScan& scan, const Line& line, const Vec2& a, const Vec2& b, const MeasureOptions& o, int* beams = nullptr);
double over_line_fsm(const sensors::LaserScan& scan, const Line& line, const Vec2& a, const Vec2& b, const MeasureOptions& o);

Measures measure(const sensors::LaserScan& scan, const Vlm& vlm, const MeasureOptions& options);
ObservationVector class_weights(const Measures& m, const MeasureOptions& options);

}  // namespace rgnav::gateway_detector
