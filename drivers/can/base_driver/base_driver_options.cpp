#include "base_driver/base_driver_options.h"

#include <cmath>

#include "canopen/protocol.h"
#include "config/duration_fields.h"

namespace rgnav::can::base {

namespace {

uint32_t clamp_counts(double counts)
{
  return static_cast<uint32_t>(std::min(std::max(std::llround(counts), 1LL), static_cast<long long>(INT32_MAX)));
}

AxisOptions load_axis(const config::Config& c, AxisOptions a)
{
  a.node_id = static_cast<uint8_t>(c.integer("node_id", a.node_id, 1, 127));
  a.counts_per_unit = c.number("counts_per_unit", a.counts_per_unit, 1.0, 1e8);
  a.sign = c.boolean("invert", a.sign < 0) ? -1 : 1;
  a.max_velocity = c.number("max_velocity", a.max_velocity, 0.01, 10.0);
  a.max_acceleration = c.number("max_acceleration", a.max_acceleration, 0.01, 50.0);
  a.quick_stop_deceleration = c.number("quick_stop_deceleration", a.quick_stop_deceleration, 0.01, 100.0);
  if (a.quick_stop_deceleration < a.max_acceleration)
    c.fail("quick_stop_deceleration", "must be >= max_acceleration (a quick stop is the fastest stop)");
  if (a.max_velocity * a.counts_per_unit > INT32_MAX) c.fail("max_velocity", "exceeds the drive's int32 velocity range");
  return a;
}

}  // namespace

int32_t AxisOptions::to_counts(double units) const
{
  const double c = std::clamp(units * counts_per_unit * sign, double(INT32_MIN), double(INT32_MAX));
  return static_cast<int32_t>(std::lround(c));
}

double AxisOptions::to_units(int64_t counts) const { return static_cast<double>(counts) * sign / counts_per_unit; }

master::DriveMasterOptions AxisOptions::drive_options(const master::DriveMasterOptions& common) const
{
  master::DriveMasterOptions d = common;
  d.node_id = node_id;
  d.profile_acceleration = clamp_counts(max_acceleration * counts_per_unit);
  d.profile_deceleration = clamp_counts(max_acceleration * counts_per_unit);
  d.quick_stop_deceleration = clamp_counts(quick_stop_deceleration * counts_per_unit);
  // Headroom over the command limit so the drive never clips a legal command.
  d.max_velocity = clamp_counts(1.1 * max_velocity * counts_per_unit);
  return d;
}

BaseDriverOptions load_base_driver_options(const config::Config& root)
{
  BaseDriverOptions o;
  const auto can = root.section("can");
  o.interface = can.choice("interface", o.interface, {"virtual", "socketcan"});
  o.socketcan_device = can.string("socketcan_device", o.socketcan_device);
  o.virtual_bus_path = can.string("virtual_bus_path", o.virtual_bus_path);
  o.virtual_client_name = can.string("virtual_client_name", o.virtual_client_name);
  if (o.interface == "virtual" && o.virtual_bus_path.size() < 2) can.fail("virtual_bus_path", "must name a socket");
  o.realtime_priority = static_cast<int>(can.integer("realtime_priority", o.realtime_priority, 0, 99));
  o.lock_memory = can.boolean("lock_memory", o.lock_memory);
  o.master.node_id = static_cast<uint8_t>(can.integer("master_node_id", o.master.node_id, 1, 127));
  o.master.sync_period = config::milliseconds(can, "sync_period_ms", o.master.sync_period, 1, 100);
  o.master.heartbeat_period = config::milliseconds(can, "master_heartbeat_ms", o.master.heartbeat_period, 5, 1000);
  o.master.sdo.timeout = config::milliseconds(can, "sdo_timeout_ms", o.master.sdo.timeout, 5, 5000);
  o.master.sdo.retries = static_cast<int>(can.integer("sdo_retries", o.master.sdo.retries, 0, 10));

  const auto drives = root.section("drives");
  auto& d = o.drive_common;
  d.master_node_id = o.master.node_id;
  d.heartbeat_period = config::milliseconds(drives, "heartbeat_period_ms", d.heartbeat_period, 5, 1000);
  d.heartbeat_timeout = config::milliseconds(drives, "heartbeat_timeout_ms", d.heartbeat_timeout, 10, 5000);
  d.master_heartbeat_timeout = config::milliseconds(drives, "master_heartbeat_timeout_ms", d.master_heartbeat_timeout, 10, 5000);
  d.pdo_timeout = config::milliseconds(drives, "pdo_timeout_ms", d.pdo_timeout, 10, 5000);
  d.fault_reset_interval = config::milliseconds(drives, "fault_reset_interval_ms", d.fault_reset_interval, 50, 60000);
  d.retry_interval = config::milliseconds(drives, "retry_interval_ms", d.retry_interval, 50, 60000);
  d.enable_timeout = config::milliseconds(drives, "enable_timeout_ms", d.enable_timeout, 100, 60000);
  // A consumer must wait longer than its producer's period, or a healthy node looks lost.
  if (d.heartbeat_timeout <= d.heartbeat_period)
    drives.fail("heartbeat_timeout_ms", "must exceed heartbeat_period_ms");
  if (d.master_heartbeat_timeout <= o.master.heartbeat_period)
    drives.fail("master_heartbeat_timeout_ms", "must exceed can.master_heartbeat_ms");
  if (d.pdo_timeout <= o.master.sync_period) drives.fail("pdo_timeout_ms", "must exceed can.sync_period_ms");
  o.translation = load_axis(drives.section("translation"), o.translation);
  o.rotation = load_axis(drives.section("rotation"), o.rotation);
  if (o.translation.node_id == o.rotation.node_id)
    drives.section("rotation").fail("node_id", "must differ from the translation drive's");
  if (o.translation.node_id == o.master.node_id || o.rotation.node_id == o.master.node_id)
    can.fail("master_node_id", "must differ from the drives' node ids");

  const auto base = root.section("base");
  o.command_deadline = config::milliseconds(base, "command_deadline_ms", o.command_deadline, 10, 2000);
  o.stop_timeout = config::milliseconds(base, "stop_timeout_ms", o.stop_timeout, 0, 10000);
  return o;
}

}  // namespace rgnav::can::base
