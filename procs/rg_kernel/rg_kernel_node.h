// Node adapter of the RG kernel: ALIGNED_SCAN and GATEWAY_EVENTS in (each written to the
// write-ahead journal before it is applied, so a restart after SIGKILL rebuilds the same
// map); RG_REGION, RG_MAP and RG_GRAPH out on change (at most every publish_period of message
// time) and at 1 Hz; rgmap.json checkpointed atomically with every publication.
#pragma once

#include <memory>
#include <string>

#include "config/config.h"
#include "persist/journal.h"
#include "procs/rg_kernel/rg_kernel.h"
#include "rgmap/rg_graph.h"
#include "rgnav/aligned_scan_t.hpp"
#include "rgnav/gateway_event_t.hpp"
#include "rgnav/rg_graph_t.hpp"
#include "rgnav/rg_map_t.hpp"
#include "runtime/node.h"

namespace rgnav::rg_kernel {

struct NodeConfig
{
  KernelOptions kernel;
  rgmap::GraphOptions graph;
  std::string state_dir;            // journal and rgmap.json; "" = no persistence (tests)
  bool fsync_each_input = true;
  double publish_period_s = 0.5;    // [s] message time between publications on change
  std::string aligned_scan = "ALIGNED_SCAN";
  std::string gateway_events = "GATEWAY_EVENTS";
  std::string rg_map = "RG_MAP";
  std::string rg_region = "RG_REGION";
  std::string rg_graph = "RG_GRAPH";
};

NodeConfig load_node_config(const config::Config& cfg, const std::string& repo_root);

class RgKernelNode
{
 public:
  RgKernelNode(runtime::Node& node, NodeConfig config);
  const RgKernel& kernel() const { return kernel_; }
  int64_t restored_inputs() const { return restored_; }
  void publish();   // publication + checkpoint (public for tests)

 private:
  enum Tag : uint32_t { kAlignedScan = 1, kGatewayEvent = 2 };
  void on_scan(const aligned_scan_t& m, bool journal);
  void on_event(const gateway_event_t& m, bool journal);
  void changed(int64_t utime);
  template <class T>
  void journal(Tag tag, const T& m);

  runtime::Node& node_;
  const NodeConfig config_;
  RgKernel kernel_;
  std::unique_ptr<persist::Journal> journal_;
  int64_t restored_ = 0;
  int64_t last_publish_utime_ = 0;
  bool unpublished_change_ = false;
};

}  // namespace rgnav::rg_kernel
