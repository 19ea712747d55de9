// The outgoing frames of one page, bounded. A client that reads slower than frames come must
// not make the server hold ever more for it, nor make anyone wait: a new frame replaces a
// queued, unsent one of the same topic (a newer pose makes the older one worthless), and when
// the queue is full anyway the oldest frame is dropped. With a capacity of at least the number
// of topics, the newest frame of every topic is always kept: a slow page shows the newest
// state, only less often. Frames are shared between clients, not copied.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>

namespace rgnav::viewer {

struct SharedFrame
{
  std::string topic;
  std::shared_ptr<const std::string> text;
};

class FrameQueue
{
 public:
  explicit FrameQueue(size_t capacity) : capacity_(capacity < 1 ? 1 : capacity) {}

  void push(SharedFrame frame);
  std::optional<SharedFrame> pop();
  size_t size() const { return frames_.size(); }
  bool empty() const { return frames_.empty(); }
  // Frames replaced or dropped unsent since construction.
  int64_t dropped() const { return dropped_; }

 private:
  size_t capacity_;
  std::deque<SharedFrame> frames_;
  int64_t dropped_ = 0;
};

}  // namespace rgnav::viewer
