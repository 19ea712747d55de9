// Node adapter of the RG kernel: ALIGNED_SCAN, GATEWAY_EVENTS and the operator's REGION_NAME in
// (each written to the write-ahead journal before it is applied, so a restart after SIGKILL
// rebuilds the same map; a name for an unknown region, or an invalid one, is dropped and
// counted, never journaled); RG_REGION, RG_MAP and RG_GRAPH out on change (at most every publish_period of message
// time) and at 1 Hz; rgmap.json exported atomically with publications (at most every
// export_period of wall time, and on a clean stop). Every snapshot_every_inputs journal
// records (200: ~100 s at the scan mapper's rate) the kernel's complete state is snapshotted
// and the journal starts a new generation (state_store.h), so a restart loads one snapshot
// and replays at most that many inputs. The journal is fsync'ed in groups, and always before
// a publication: what was published is durable.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "config/config.h"
#include "config/robot_description.h"
#include "procs/rg_kernel/rg_kernel.h"
#include "procs/rg_kernel/state_store.h"
#include "rgmap/rg_graph.h"
#include "rgnav/aligned_scan_t.hpp"
#include "rgnav/gateway_event_t.hpp"
#include "rgnav/objects3d_t.hpp"
#include "rgnav/rg_graph_t.hpp"
#include "rgnav/region_name_t.hpp"
#include "rgnav/rg_map_t.hpp"
#include "runtime/node.h"

namespace rgnav::rg_kernel {

struct NodeConfig
{
  KernelOptions kernel;
  rgmap::GraphOptions graph;
  std::string state_dir;            // journal, snapshots and rgmap.json; "" = no persistence (tests)
  int sync_every_inputs = 20;       // group commit: fsync after this many inputs ...
  double sync_period_s = 0.1;       // [s] ... or this long (wall time) after the oldest unsynced one
  int64_t snapshot_every_inputs = 200;   // journal records between snapshots (0: never)
  double export_period_s = 1.0;     // [s] wall time between rgmap.json exports at most (and on stop)
  double publish_period_s = 0.5;    // [s] message time between publications on change
  std::string aligned_scan = "ALIGNED_SCAN";
  std::string gateway_events = "GATEWAY_EVENTS";
  std::string rg_map = "RG_MAP";
  std::string rg_region = "RG_REGION";
  std::string rg_graph = "RG_GRAPH";
  std::string region_name = "REGION_NAME";   // the operator's region names ("" = not subscribed)
  std::string objects3d = "OBJECTS_3D";      // the vision's 3D rectangles ("" = not subscribed)
};

// The kernel's options (rg_kernel_options.h, with the robot description's radius) and the
// node's own: persistence, publish, channels.
NodeConfig load_node_config(const config::Config& cfg, const config::RobotDescription& robot, const std::string& repo_root);

class RgKernelNode
{
 public:
  RgKernelNode(runtime::Node& node, NodeConfig config);
  ~RgKernelNode();
  RgKernelNode(const RgKernelNode&) = delete;
  RgKernelNode& operator=(const RgKernelNode&) = delete;
  const RgKernel& kernel() const { return kernel_; }
  // Inputs the restored state holds (snapshot + journal tail); 0 on a fresh start.
  int64_t restored_inputs() const { return restored_; }
  int64_t replayed_from_journal() const { return replayed_; }
  int64_t snapshot_generation() const { return loaded_generation_; }
  void publish();   // publication + checkpoint (public for tests)
  // Snapshot now (the journal starts a new generation) and wait until it is durable (tests,
  // tools); normally snapshots are taken every snapshot_every_inputs inputs in the background.
  void snapshot_now();
  StateStore* store() { return store_.get(); }

 private:
  // kObjects3dInMap: an OBJECTS_3D message whose odom_from_base holds the map pose it was
  // re-anchored to (the scan mapper's correction by scan id is live state a replay lacks).
  enum Tag : uint32_t { kAlignedScan = 1, kGatewayEvent = 2, kRegionName = 3, kObjects3dInMap = 4 };
  void on_scan(const aligned_scan_t& m, bool journal);
  void on_objects(objects3d_t m, bool journal);
  void on_event(const gateway_event_t& m, bool journal);
  void on_region_name(const region_name_t& m, bool journal);
  void changed(int64_t utime);
  template <class T>
  void journal(Tag tag, const T& m);
  void restore();
  void write_export(const rgmap::RgMap& map);
  void maybe_snapshot();
  std::string snapshot_payload() const;
  void apply_snapshot(const std::string& payload);

  runtime::Node& node_;
  const NodeConfig config_;
  RgKernel kernel_;
  std::unique_ptr<StateStore> store_;
  int64_t inputs_ = 0;              // inputs journaled since the map was started (all runs)
  int64_t restored_ = 0;
  int64_t replayed_ = 0;
  int64_t loaded_generation_ = 0;
  int64_t last_publish_utime_ = 0;
  bool unpublished_change_ = false;
  bool replaying_ = false;
  bool export_pending_ = false;
  // The scan mapper's correction (map_from_odom) of recent scans by id, to re-anchor the
  // vision's objects to the scan taken at capture (diss. 3.3.5).
  std::map<int64_t, geometry::Pose2> map_from_odom_;
  std::chrono::steady_clock::time_point last_export_{};
};

}  // namespace rgnav::rg_kernel
