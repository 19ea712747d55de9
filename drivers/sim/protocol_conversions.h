// Drive units <-> simulator units for protocol mode. The CiA 402 drives speak counts and
// counts/s; the scale (counts per m of wheel travel, per rad of steering) and the sign are
// base_driver's own AxisOptions, loaded from the same base_driver config the driver reads, so
// the simulated encoders and the driver can never disagree about a count.
//
// What the encoders measure is the simulator's *odometry* (OdometryModel: scale errors,
// heading bias, random walks), not the true motion: a real wheel encoder counts slip and a
// wrong wheel radius along with the motion, so the odometry error belongs in the counts.
#pragma once

#include "can/base_driver/base_driver_options.h"
#include "sim/simulator.h"

namespace rgnav::sim {

struct DriveAxes
{
  can::base::AxisOptions translation;  // units: m
  can::base::AxisOptions rotation;     // units: rad
};

// counts (or counts/s) -> m or rad (or per s), the drive's sign applied; not rounded.
double counts_to_units(double counts, const can::base::AxisOptions& axis);
double units_to_counts(double units, const can::base::AxisOptions& axis);

// The synchro drive's command from the two drives' demand velocities [counts/s].
DriveCommand command_from_demands(double translation_counts_per_s, double rotation_counts_per_s,
                                  const DriveAxes& axes);

struct EncoderReading
{
  double velocity = 0.0;  // [counts/s] what 0x606C reports
  double position = 0.0;  // [counts] what 0x6064 reports (the drive wraps it to int32)
};

struct EncoderReadings
{
  EncoderReading translation;
  EncoderReading rotation;
};

// The encoders of the simulated base now: positions are the odometry model's cumulative
// measured translation / rotation; velocities the drive's, with the odometry model's
// systematic errors (its random walk is integrated in the positions only: differentiated
// over one physics step it would be far noisier than a real velocity estimate).
EncoderReadings encoder_readings(const Simulator& sim, const DriveAxes& axes);

}  // namespace rgnav::sim
