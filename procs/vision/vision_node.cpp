#include "vision/vision_node.h"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "bus/lcm_bus.h"
#include "config/config.h"
#include "drivers/stereo/image_encoding.h"
#include "msg/conversions.h"
#include "rgnav/heartbeat_t.hpp"
#include "vision/vision_conversions.h"

namespace rgnav::vision {

namespace {

// utime beyond this is refused, so that differences of them cannot overflow.
constexpr int64_t kMaxStamp = int64_t{1} << 62;
bool stamp_ok(int64_t v) { return v > 0 && v < kMaxStamp; }

VisionPipeline make_pipeline(const StereoRig& rig, const VisionNodeOptions& options)
{
  if (const std::string why = check_rig(rig); !why.empty())
    throw config::ConfigError(options.calibration_file + ": " + why);
  return VisionPipeline(rig, options.vision);
}

FrameSyncOptions sync_options(const VisionNodeOptions& o) { return {o.max_pose_gap, o.laser_period, o.base_from_laser}; }

}  // namespace

VisionNode::VisionNode(runtime::Node& node, const VisionNodeOptions& options, const StereoRig& rig)
    : node_(node),
      options_(options),
      pipeline_(make_pipeline(rig, options)),
      sync_(pipeline_, sync_options(options),
            {[this](const StereoFrame& f, const FrameResult& r) { on_processed(f, r); },
             [this](const std::string& why) { drop_frame(why); },
             [this](const std::string& why) { node_.drops().drop(options_.channels.laser, why); },
             [this] { node_.note_progress(); }})
{
  const auto& ch = options_.channels;
  const auto stereo = node_.subscribe<stereo_images_t>(ch.stereo, [this](const stereo_images_t& m) { on_stereo(m); });
  // A frame that waited behind others is worth less than the newest one: LCM keeps only a few
  // (older ones are dropped in its queue), so a slow frame never builds a backlog of images that
  // also crowds the odometry out of the receive buffer.
  if (auto* lcm = dynamic_cast<bus::LcmBus*>(&node_.bus())) lcm->set_queue_capacity(stereo, options_.frame_queue);
  node_.subscribe<odometry_t>(ch.odometry, [this](const odometry_t& m) { on_odometry(m); });
  node_.subscribe<laser_scan_t>(ch.laser, [this](const laser_scan_t& m) { on_laser(m); });
  node_.every(std::chrono::milliseconds(500), [this] { report(); });
  const RectifiedCamera& cam = pipeline_.camera();
  spdlog::info("calibration {} ({}x{}, f {:.1f} px, baseline {:.3f} m{}), map of {:.2f} m voxels within {:.1f} m",
               options_.calibration_file, cam.size.width, cam.size.height, cam.focal, cam.baseline,
               pipeline_.rectifier_identity() ? ", already rectified" : "", options_.vision.map.resolution,
               options_.vision.map.keep_radius);
  report();
}

void VisionNode::drop_frame(const std::string& why) { node_.drops().drop(options_.channels.stereo, why); }

void VisionNode::on_stereo(const stereo_images_t& m)
{
  if (!stamp_ok(m.utime)) return drop_frame("frame utime out of range");
  if (m.calibration_id != options_.calibration_id)
    return drop_frame(fmt::format("frame {} needs calibration '{}', this process has '{}'", m.frame_id, m.calibration_id,
                                  options_.calibration_id));
  if (m.utime <= last_frame_utime_) return drop_frame(fmt::format("frame {} not newer than the last one", m.frame_id));
  if (!std::isfinite(m.pan) || !std::isfinite(m.tilt) || std::abs(m.pan) > 2 * M_PI || std::abs(m.tilt) > M_PI / 2)
    return drop_frame(fmt::format("frame {}: head angles out of range", m.frame_id));
  auto left = stereo::decode_image(m.left);
  auto right = stereo::decode_image(m.right);
  if (!left || !right) return drop_frame(fmt::format("frame {}: an image does not decode", m.frame_id));
  const cv::Size size = pipeline_.rig().image_size;
  if (left->size() != size || right->size() != size)
    return drop_frame(fmt::format("frame {}: images {}x{} / {}x{}, the calibration is for {}x{}", m.frame_id, left->cols,
                                  left->rows, right->cols, right->rows, size.width, size.height));
  last_frame_utime_ = m.utime;
  StereoFrame f;
  f.utime = m.utime;
  f.left = std::move(*left);
  f.right = std::move(*right);
  f.pan = m.pan;
  f.tilt = m.tilt;
  sync_.on_frame(std::move(f));
}

void VisionNode::on_odometry(const odometry_t& m)
{
  if (!stamp_ok(m.utime) || m.seq < 0) return node_.drops().drop(options_.channels.odometry, "odometry utime or seq out of range");
  sync_.on_odometry(m.utime, m.seq, msg::to_pose2(m.odom_from_base));
}

void VisionNode::on_processed(const StereoFrame& f, const FrameResult& r)
{
  last_ = r;
  last_frame_wall_ = std::chrono::steady_clock::now();
  node_.publish(options_.channels.obstacles, to_msg(last_.grid));
  if (last_.rectangles_run)
    node_.publish(options_.channels.objects,
                  to_msg(last_.rectangles, f.utime, sync_.frames_processed(), last_scan_id_, f.odom_from_base));
  node_.note_progress();
  spdlog::debug("frame at {}: {:.0f} ms ({} points), {:.3f} s behind the odometry", f.utime, last_.total_ms, last_.points,
                sync_.odometry_lead_s(f.utime));
}

void VisionNode::on_laser(const laser_scan_t& m)
{
  if (!stamp_ok(m.utime)) return node_.drops().drop(options_.channels.laser, "scan utime out of range");
  last_scan_id_ = std::max(last_scan_id_, m.scan_id);
  sync_.on_laser(msg::to_laser_scan(m));
}

void VisionNode::report()
{
  const auto& map = pipeline_.map();
  std::string text = fmt::format("{} frames ({} superseded), last {:.0f} ms, {} points; {} scans fused; map {} leaves, {:.1f} MB",
                                 frames_processed(), frames_superseded(), last_.total_ms, last_.points, laser_scans_fused(), map.leaf_count(),
                                 static_cast<double>(map.memory_bytes()) / 1e6);
  const bool stale = frames_processed() == 0 || std::chrono::steady_clock::now() - last_frame_wall_ >
                                         std::chrono::duration<double>(options_.stale_after);
  if (stale) text += frames_processed() == 0 ? "; no frame processed yet" : "; no frame processed lately";
  if (text == reported_) return;
  reported_ = text;
  node_.set_status(stale ? heartbeat_t::STATE_DEGRADED : heartbeat_t::STATE_RUNNING, text);
}

}  // namespace rgnav::vision
