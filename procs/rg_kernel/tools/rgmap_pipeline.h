// The RG mapping pipeline in one thread, without LCM: scans and odometry go to the scan mapper;
// every accepted scan (and every loop-closure correction of an earlier one) goes to the RG
// kernel as the ALIGNED_SCAN the live scan_mapper would publish; every new accepted scan also
// goes to the gateway detector (as configured for aligned input), whose events go to the kernel
// after the scan they came from — the order the live processes see them in on the bus
// (deploy/launch/demo.pmd). Everything runs on message time: the same inputs give the same map.
#pragma once

#include <optional>
#include <vector>

#include "gateway_detector/gateway_detector.h"
#include "pipeline_options.h"
#include "procs/rg_kernel/rg_kernel.h"
#include "scan_mapper/scan_mapper.h"

namespace rgnav::rgmap_pipeline {

struct PipelineCounts
{
  int64_t scans_in = 0;
  int64_t aligned = 0;          // accepted scans passed on
  int64_t corrections = 0;      // republished earlier scans (loop closures)
  int64_t events = 0;           // gateway events from the detector
  int64_t traversals = 0;       // ... of which TRAVERSED
  int64_t kernel_changes = 0;   // inputs that changed the map
};

class RgMapPipeline
{
 public:
  RgMapPipeline(const PipelineOptions& options, gateway_detector::HmmClassifier classifier = {});

  void add_odometry(const scan_mapper::OdometrySample& sample);
  void add_scan(const sensors::LaserScan& scan);

  // Accepted scans with their final pose estimates (given poses: the odometry at the scan).
  std::vector<scan_mapper::ScanNode> nodes() const;
  scan_mapper::MapperStats mapper_stats() const;
  const rg_kernel::RgKernel& kernel() const { return kernel_; }
  const PipelineCounts& counts() const { return counts_; }
  const PipelineOptions& options() const { return options_; }
  // The newest accepted scan as it was passed on (its pose then: what SLAM_POSE said of it;
  // nullptr before the first), and what the gateway detector made of it (GATEWAY_HYPOTHESES).
  const scan_mapper::ScanNode* last_aligned() const { return last_aligned_ ? &*last_aligned_ : nullptr; }
  const gateway_detector::DetectorOutput& last_detection() const { return last_detection_; }
  // The map as the live RG kernel publishes it (RgKernel::refreshed_map).
  const rgmap::RgMap& refreshed_map() { return kernel_.refreshed_map(); }

 private:
  void pass_on(const scan_mapper::ScanNode& node);
  void correct(const scan_mapper::ScanNode& node);
  void add_given_pose_scan(const sensors::LaserScan& scan);

  const PipelineOptions options_;
  scan_mapper::ScanMapper mapper_;
  gateway_detector::GatewayDetector detector_;
  rg_kernel::RgKernel kernel_;
  PipelineCounts counts_;
  std::optional<scan_mapper::ScanNode> last_aligned_;
  gateway_detector::DetectorOutput last_detection_;
  // Given-poses mode: the newest pose sample and the gated scans (the scan mapper is not used).
  std::optional<scan_mapper::OdometrySample> last_odometry_;
  std::vector<scan_mapper::ScanNode> given_;
  scan_mapper::MapperStats given_stats_;
};

}  // namespace rgnav::rgmap_pipeline
