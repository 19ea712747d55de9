// Options of the offline RG mapping pipeline: the scan mapper's, the gateway detector's and the
// RG kernel's, each loaded from its own process config (config/scan_mapper.yaml,
// config/gateway_detector_aligned.yaml, config/rg_kernel.yaml) by that process's own loader
// with the robot description (config/robot.yaml), so the offline tool and the live processes
// can never disagree about a parameter.
#pragma once

#include <string>

#include "config/robot_description.h"
#include "gateway_detector/gateway_detector.h"
#include "gateway_detector/hmm.h"
#include "procs/rg_kernel/rg_kernel.h"
#include "rgmap/rg_graph.h"
#include "scan_mapper/scan_mapper_options.h"

namespace rgnav::rgmap_pipeline {

struct PipelineOptions
{
  scan_mapper::ScanMapperOptions mapper;
  gateway_detector::DetectorOptions detector;
  rg_kernel::KernelOptions kernel;
  rgmap::GraphOptions graph;
  // true: the log's odometry is taken as the map pose (logs whose odometry was already
  // corrected, as the dissertation used them in ch. 6): each scan gets the newest pose sample
  // before it in input order; scans are still gated like the scan mapper gates them.
  // false: the scan mapper estimates the poses.
  bool poses_as_given = false;
};

struct PipelineConfigPaths
{
  std::string scan_mapper;       // config/scan_mapper.yaml
  std::string gateway_detector;  // config/gateway_detector_aligned.yaml
  std::string rg_kernel;         // config/rg_kernel.yaml
  std::string robot;             // config/robot.yaml
};

struct LoadedPipeline
{
  config::RobotDescription robot;
  PipelineOptions options;
  gateway_detector::HmmClassifier classifier;  // empty: crossings classified by their weights
  std::string classifier_note;                 // where the models came from, or why there are none
};

// Throws config::ConfigError naming the file and key of the first bad value, or the keys nobody
// reads outside the live processes' own sections (node, channels, ...), and when the gateway
// models were trained with other measure weights than the detector config uses.
LoadedPipeline load_pipeline(const PipelineConfigPaths& paths);

}  // namespace rgnav::rgmap_pipeline
