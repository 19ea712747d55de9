#include "viewer/frame_queue.h"

namespace rgnav::viewer {

void FrameQueue::push(SharedFrame frame)
{
  for (auto& queued : frames_) {
    if (queued.topic == frame.topic) {
      // In place: the topic keeps its turn, so a steady pose stream cannot starve the map.
      queued = std::move(frame);
      ++dropped_;
      return;
    }
  }
  if (frames_.size() >= capacity_) {
    frames_.pop_front();
    ++dropped_;
  }
  frames_.push_back(std::move(frame));
}

std::optional<SharedFrame> FrameQueue::pop()
{
  if (frames_.empty()) return std::nullopt;
  SharedFrame f = std::move(frames_.front());
  frames_.pop_front();
  return f;
}

}  // namespace rgnav::viewer
