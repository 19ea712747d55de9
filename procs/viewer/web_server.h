// The viewer's HTTP and WebSocket server (Boost.Beast; no LCM): serves the page's files from one
// folder and streams frames to every page connected at /ws. It runs on a thread of its own, so
// nothing a client does (read slowly, stall, send garbage) reaches the caller: publish() only
// posts the frame to that thread, and each client has its own bounded queue (frame_queue.h).
// A client that sends anything but a well-formed goal or cancel (client_input.h), or a binary
// or oversized frame, is closed; the others go on. WebSocket upgrades from a page of another
// origin are refused (a web site open in the operator's browser must not drive the robot).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "viewer/client_input.h"

namespace rgnav::viewer {

struct ServerOptions
{
  std::string address = "127.0.0.1";   // loopback unless configured otherwise
  uint16_t port = 8036;                // 0 = any free port (tests)
  std::string web_root;                // folder of index.html and what it loads
  std::string goal_token;              // goals from other hosts need it ("" = refused)
  size_t queue_frames = 16;            // per client
  size_t max_clients = 16;
  size_t max_input_bytes = 4096;       // a larger frame from a page closes it
};

struct ServerStats
{
  int64_t clients = 0;                 // connected now
  int64_t accepted = 0;                // since start
  int64_t frames_sent = 0;
  int64_t frames_dropped = 0;          // replaced or dropped unsent in a slow client's queue
  int64_t closed_malformed = 0;        // clients closed for what they sent
  int64_t refused = 0;                 // upgrades refused (origin, too many clients)
  int64_t goals = 0;                   // goals and cancels handed on
};

struct ClientGoal
{
  uint64_t client = 0;
  bool from_loopback = false;
  GoalRequest request;
};

class WebServer
{
 public:
  // Runs on the server thread for every allowed goal or cancel; returns "" when taken, else why
  // not (the page is told).
  using GoalHandler = std::function<std::string(const ClientGoal&)>;

  WebServer(ServerOptions options, GoalHandler on_goal);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  // Reads the page's files, binds and starts the thread. Throws std::runtime_error naming the
  // address or the folder when it cannot.
  void start();
  void stop();
  uint16_t port() const;

  // Any thread. The newest frame of each topic is also kept for pages that connect later.
  void publish(const std::string& topic, std::string text);
  ServerStats stats() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rgnav::viewer
