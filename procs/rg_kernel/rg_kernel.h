// The RG kernel's algorithm (diss. 5.0, 5.2, 6.1), no LCM: aligned scans are stacked into the
// current region; a traversed gateway finalises the region (line map, bounding rectangle,
// freespace from in-region beams: each beam ends at every gateway of the map and at the doorways
// of the region's line map its robot never went through, gateway_geometry.h, doorways.h, and what
// it saw only through a passage narrower than a door is cut off, freespace_trim.h) and
// opens the region beyond, or re-enters a known one; a doorway of the line map the robot does go
// through where no gateway is known is crossed like a reported gateway (one the detector missed),
// and so are a known door of the current region gone back through unreported and the stem side
// of a T-junction the region lies beyond, left into the junction unreported; a
// region that turns out to be a known place (the robot's positions lie in a finalised
// region's own space, seen by that region's robot: known_place.h) is merged into it and gateways with one region on both sides are
// neutralized (diss. 6.1.1); a region whose robot, from a new place, walks on into a known
// region's place with no gateway between crosses one there (the missed gateway of diss. 6.1.1,
// Fig. 6.4, split rather than merged); republished scans (loop-closure corrections) update their region.
// Traversals (gateway_traversal.cpp): a crossing (junction outline) joins one pair of regions
// per gateway, the branches its first traversal took; left into another branch it gets a
// gateway of its own with the same outline. A junction entered or left through a door just
// crossed is that door's crossing reported again; a junction gone straight through whose sides
// are walled in the line map has no branch (walled_crossing.cpp); a region beyond the stem of a
// T-junction ends at that side (the junction is the hallway's). Scans taken beyond one of the
// region's own doors, or inside such a junction, carve no freespace into it (region_builder.h,
// ForeignSide).
// A new line gateway, whoever reports it, splits the region only where it narrows the free space
// (narrowing.h): a cut across a hallway as narrow as a door is ignored. Scan points another scan
// saw through (something that moved) are no part of any line map (region_builder.h,
// seen_through.h). The rules, what each fixes
// and what switching it off changes: procs/rg_kernel/README.md.
// Inputs are applied in the order given; with the same inputs the map is the same.
#pragma once

#include <functional>
#include <map>
#include <set>
#include <vector>

#include "procs/rg_kernel/known_place.h"
#include "procs/rg_kernel/narrowing.h"
#include "procs/rg_kernel/objects3d.h"
#include "procs/rg_kernel/region_builder.h"
#include "rgmap/rg_map.h"

namespace rgnav::rg_kernel {

// RgKernel::beam_limits.
struct BeamLimits
{
  RegionBuilder::GatewayLines lines;
  std::vector<ForeignSide> foreign;
};

struct KernelOptions
{
  RegionBuildOptions build;
  double gateway_match_distance = 0.8;   // [m] crossing points closer than this: same gateway
  int merge_min_scans = 8;               // scans in a region before a merge is considered
  double merge_inside_ratio = 0.7;       // share of its robot positions seen by a known region's robot
  int merge_recent_scans = 20;           // ... and of its last this many positions (all, if fewer) ...
  double merge_recent_ratio = 0.9;       // ... at least this share: the robot is in that place now. A branch or
                                         // room entered at a junction has its first positions in the junction,
                                         // which the region before saw (rooms off a junction: most were merged into the hallway)
  // A region whose robot, after merge_min_scans positions in a new place, has this many positions
  // in a row (the newest) in one known region's place, with no gateway between, walked into it
  // through a gateway nobody saw: the kernel crosses one there, a line across the step into the
  // known place reaching to the line map's walls (at most entry_max_half_width each side), and the
  // positions from the step on are the known region's (a corridor's region otherwise runs on across
  // the hall it opens into, though the hall's region is known). Not merged: the new place stays a
  // region of its own. 0: off.
  int entry_min_scans = 8;
  // [m] ... and the farthest of them at least this far from the step in: a junction's square is
  // every region's place whose robot went through it (a robot going straight through a 2 m
  // junction another region's robot crossed has not walked into that region).
  double entry_min_depth = 3.0;
  double entry_max_half_width = 1.5;     // [m]
  KnownPlaceOptions known_place;         // what makes a position part of a known region (known_place.h)
  double late_scan_reach = 3.0;          // [m] scans this far past a crossed gateway belong beyond it
  double junction_side_reach = 2.0;      // [m] robot this near outside a crossing's side: its region lies beyond
  double junction_side_min_depth = 0.15; // [m] ... and at least this far past it (gateway_geometry.h, SideReach)
  // [m] A crossing gone straight through whose sides along the way (in the current region's line
  // map) are open over less than this (or 80 % of the side, if shorter) has no branch: the
  // detector took doors in the hallway walls, or a room's wall seen through one for the far
  // side, for a junction (issue 8: spurious crossings cut hallways). Doors are at most 1.3 m.
  double min_branch_width = 1.4;
  double branch_wall_tolerance = 0.25;   // [m] a wall segment this near a side's line runs along it
  // A region beyond the stem side of a T-junction (the side opposite walled, a hallway open past
  // it, by min_branch_width in the region's line map) ends at that side, and its scans inside the
  // junction carve nothing: the junction's square is the hallway's (issue 8: rooms and bays with
  // wide openings onto a hallway took the hallway's junctions into their freespace).
  bool stem_ends_branch = true;
  // So does a region beyond a side of an X-crossing with a hallway open past it (the side opposite
  // open too: another branch), but the region the robot first came into the junction from
  // (junction_owner), which keeps the square: a room's square across a narrow hallway from
  // another room's (cubicles facing each other) is the hallway's.
  bool x_branches_end = true;
  bool doorway_gateways = true;          // a doorway of the line map (build.doorways) the robot goes through is a gateway
  bool door_exits = true;                // a known door of the current region the robot goes through unreported is crossed
  // So is the stem side of a T-junction the region lies beyond, into the junction (not an X's branch
  // side: across an X the robot may go on into the branch opposite, the detector's report decides).
  bool stem_exits = true;
  // [m] a gateway line (not an outline) ends beams this far beyond its points too: the detector's
  // and the line map's door points lie on the jambs' visible edges, and beams grazing past them
  // into the room behind carved it into the region in front (issue 8: seen-through losses).
  double gateway_line_extension = 0.5;
  Objects3dOptions objects3d;            // the vision's 3D rectangles (objects3d.h)
  // A new line gateway (the detector's door or narrow passage, a doorway of the line map, the
  // entry_min_scans step) splits the region only where it narrows the free space (narrowing.h).
  NarrowingOptions narrowing;
};

struct ScanInput
{
  int64_t scan_id = 0;
  int64_t utime = 0;
  int32_t revision = 0;
  geometry::Pose2 map_from_base;
  geometry::Pose2 base_from_laser;
  std::vector<Eigen::Vector2d> laser_points;   // valid end points, laser frame, beam order
};

struct GatewayEventInput
{
  enum class Kind { kApproached = 1, kEntered = 2, kTraversed = 3, kLost = 4 };
  int64_t utime = 0;
  int64_t scan_id = 0;
  Kind kind = Kind::kTraversed;
  int64_t track_id = 0;
  rgmap::GatewayClass cls = rgmap::GatewayClass::kUnknown;
  geometry::Pose2 map_from_base;               // robot pose at the event
  std::vector<Eigen::Vector2d> gateway_points; // map frame
  double direction = 0;                        // [rad] map frame, heading of the crossing
};

struct KernelStats
{
  int regions = 0;          // not merged away
  int gateways = 0;
  int neutralized = 0;
  int segments = 0;
  int64_t raw_points = 0;
  double compression = 0;   // raw points / segment end points
};

class RgKernel
{
 public:
  explicit RgKernel(KernelOptions options);

  // Both return true when the map changed.
  bool add_scan(const ScanInput& scan);
  bool add_gateway_event(const GatewayEventInput& event);
  // 3D rectangles the vision saw (map frame: the node re-anchors them by scan id) into the
  // current region's objects (objects3d.h). True when the map changed.
  bool add_objects3d(int64_t utime, const std::vector<rgmap::Rectangle3d>& in_map_frame);
  // The operator's name for a region (a region merged away names the one it was merged into).
  // True when the map changed (its version goes up); false with *why set when refused (no such
  // live region, not a valid name, another live region's name: rgmap::region_to_name), false
  // with *why empty when the region has that name already.
  bool name_region(int64_t region_id, const std::string& name, std::string* why);

  const rgmap::RgMap& map() const { return map_; }
  // The map with the description (segments, bbox, freespace) of every region that changed
  // since the last call brought up to date. After a loop closure that is every region it
  // corrected; between_regions (if set) is called after each, so that a process can show it is
  // alive meanwhile.
  const rgmap::RgMap& refreshed_map(const std::function<void()>& between_regions = {});
  // Called between the steps of a gateway traversal (finalising the region left, looking for
  // the known region beyond), each up to a few hundred ms on a loaded core, so that a process
  // can show it is alive meanwhile (the demo's supervisor once took the kernel for hung there).
  // The regions' builders call it too, once per scan, while they work through a whole region.
  void set_progress(std::function<void()> progress);
  size_t stale_regions() const { return dirty_.size(); }
  // Same, computed from scratch for every region (tests, offline tools).
  rgmap::RgMap described_map() const;
  rgmap::Region describe_region(int64_t id) const;
  KernelStats stats() const;
  // Robot (laser) positions of a live region's scans in the map frame, oldest first (evaluation).
  std::vector<Eigen::Vector2d> robot_positions(int64_t region_id) const;
  // How well the regions' line maps describe their scans (all regions not merged away).
  LineMapFidelity line_map_fidelity(double tolerance = 0.05, double cap = 0.5) const;

  // The kernel's complete state (map, every region's scans and derived caches, bookkeeping):
  // a kernel restored from it continues exactly as this one would, input for input. Not the
  // options: the restoring kernel is built with its own (the same config).
  void save_state(persist::ByteWriter& w) const;
  std::string snapshot() const;
  // Replaces this kernel's state with the one at r's position, which must run to r's end;
  // throws persist::CorruptBytes (state unchanged) if it is malformed.
  void restore_state(persist::ByteReader& r);
  void restore(const std::string& snapshot_bytes);

 private:
  int64_t open_region(const geometry::Pose2& map_from_region, int64_t utime);
  void enter(int64_t region_id, int64_t utime, const Eigen::Vector2d& robot);
  void maybe_merge_current(int64_t utime);
  // The entry_min_scans rule (KernelOptions): `positions` are the current region's robot
  // positions (map frame, oldest first), `holding` the known region holding each (0: none).
  void maybe_cross_into_known_place(const std::vector<Eigen::Vector2d>& positions, const std::vector<int64_t>& holding);
  // A traversal (add_gateway_event) handing on the current region's newest scans `handed_on`
  // (oldest first, a trailing run of scan_ids_by_time) as well as those past the gateway, into
  // region `into` if not 0.
  bool traverse(const GatewayEventInput& e, const std::vector<int64_t>& handed_on, int64_t into);
  // What bounds region_id's beams (its frame): the lines of every non-neutralized gateway of the
  // map (gateway_geometry.h) that end them, and the places where its scans carve nothing (the far
  // sides of its own traversed doors, the insides of the junctions whose stem it lies beyond).
  // `robot` (map frame), if given, counts as one of its robot positions (the region just entered
  // has none yet).
  BeamLimits beam_limits(int64_t region_id, const Eigen::Vector2d* robot = nullptr) const;
  // The region the robot came from when it first crossed the junction g belongs to: region_a of
  // the first gateway with g's outline.
  int64_t junction_owner(const rgmap::Gateway& g) const;
  SideReach side_reach() const { return {options_.junction_side_reach, options_.junction_side_min_depth}; }
  // The region's description (RegionBuilder::describe) within its beam limits.
  void describe(int64_t region_id, rgmap::Region* region, bool exact) const;
  void mark_regions_behind(const rgmap::Gateway& g);
  // The robot's last step (from, map frame, to the scan s) went through a door unreported: a known
  // door of the current region to its far side (door_exits), the stem side of a known T-junction
  // the region lies beyond into the junction (stem_exits), or a doorway of its line map no
  // gateway stands in (doorway_gateways); crossed as the detector would have reported it.
  void walk_through_door(const Eigen::Vector2d& from, const ScanInput& s);
  bool repeats_entry(const rgmap::Gateway& g, int64_t current, double direction) const;
  // A traversed line gateway's unit normal (map frame) pointing to region_b's side: the side its
  // first traversal headed to.
  Eigen::Vector2d line_normal_to_b(const rgmap::Gateway& g) const;
  // The region a traversal of the known gateway g from `current` with `direction` [rad, map]
  // leads to, 0 if g does not join `current` to the region ahead.
  int64_t leads_to(const rgmap::Gateway& g, int64_t current, double direction) const;
  // The door of the current region just crossed that lies in a side of the junction traversal
  // `e` went through (the same crossing reported again), 0 if none.
  int64_t door_on_junction_side(const GatewayEventInput& e, int64_t current) const;
  // Whether the crossing traversal `e` went straight between walls: every side of its outline
  // along the heading is walled in the current region's line map (no branch-wide opening).
  bool walled_crossing(const GatewayEventInput& e, int64_t current) const;
  // The free widths about the line traversal `e` (two points) crossed, in the current region's
  // line map (narrowing.h).
  NarrowingProfile narrowing_of(const GatewayEventInput& e, int64_t current) const;
  Eigen::Vector2d crossing_in_map(const rgmap::Gateway& g) const;
  std::vector<int64_t> scans_past_gateway(int64_t region_id, const GatewayEventInput& e) const;
  StoredScan to_stored(const ScanInput& s, int64_t region_id) const;

  const KernelOptions options_;
  rgmap::RgMap map_;
  std::map<int64_t, RegionBuilder> builders_;   // by region id
  std::map<int64_t, int64_t> region_of_scan_;   // scan id -> region holding it
  std::map<int64_t, ScanInput> scan_inputs_;    // latest revision of every scan (for re-framing on merge)
  std::map<int64_t, int64_t> entered_utime_;    // track id -> ENTERED time, for traversal times
  int scans_since_entering_ = 0;
  std::set<int64_t> dirty_;                     // regions whose description is stale
  std::function<void()> progress_;   // set_progress
};

}  // namespace rgnav::rg_kernel
