// The viewer's server over real loopback sockets, with Beast clients: the page is served, frames
// reach every page, a page that does not read never holds up the others (its frames are
// dropped, the queue stays bounded), malformed input closes that page only, goals reach the
// handler, and pages of another origin are refused.
#include <gtest/gtest.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "viewer/web_server.h"

namespace rgnav::viewer {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using nlohmann::json;

ServerOptions test_options()
{
  ServerOptions o;
  o.address = "127.0.0.1";
  o.port = 0;
  o.web_root = RGNAV_VIEWER_WEB_ROOT;
  o.queue_frames = 16;
  return o;
}

// A blocking WebSocket client.
struct Client
{
  net::io_context ioc;
  websocket::stream<tcp::socket> ws{ioc};

  explicit Client(uint16_t port, const std::string& origin = "")
  {
    tcp::resolver resolver(ioc);
    net::connect(ws.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
    ws.set_option(websocket::stream_base::decorator([origin](websocket::request_type& req) {
      if (!origin.empty()) req.set(http::field::origin, origin);
    }));
    ws.handshake("127.0.0.1:" + std::to_string(port), "/ws");
  }
  // The next frame, as JSON; throws when the connection ends.
  json next()
  {
    beast::flat_buffer b;
    ws.read(b);
    return json::parse(beast::buffers_to_string(b.data()));
  }
  // Reads until a frame of `type` (skipping others), at most `limit` frames.
  json next_of(const std::string& type, int limit = 1000)
  {
    for (int i = 0; i < limit; ++i) {
      json j = next();
      if (j["type"] == type) return j;
    }
    throw std::runtime_error("no " + type + " frame");
  }
};

std::string http_get(uint16_t port, const std::string& target, http::status* status)
{
  net::io_context ioc;
  beast::tcp_stream stream(ioc);
  tcp::resolver resolver(ioc);
  stream.connect(resolver.resolve("127.0.0.1", std::to_string(port)));
  http::request<http::empty_body> req{http::verb::get, target, 11};
  req.set(http::field::host, "127.0.0.1");
  http::write(stream, req);
  beast::flat_buffer b;
  http::response<http::string_body> res;
  http::read(stream, b, res);
  *status = res.result();
  return res.body();
}

TEST(ViewerWebServer, ServesThePageAndNothingOutsideItsFolder)
{
  WebServer server(test_options(), nullptr);
  server.start();
  ASSERT_GT(server.port(), 0);
  http::status s;
  const std::string page = http_get(server.port(), "/", &s);
  EXPECT_EQ(s, http::status::ok);
  EXPECT_NE(page.find("<canvas"), std::string::npos);
  http_get(server.port(), "/../CMakeLists.txt", &s);
  EXPECT_EQ(s, http::status::not_found);
  http_get(server.port(), "/%2e%2e/CMakeLists.txt", &s);
  EXPECT_EQ(s, http::status::not_found);
}

TEST(ViewerWebServer, RefusesAWebRootWithoutAPageAndABadAddress)
{
  auto o = test_options();
  o.web_root = "/nonexistent-viewer-root";
  EXPECT_THROW(WebServer(o, nullptr).start(), std::runtime_error);
  o = test_options();
  o.address = "not-an-address";
  EXPECT_THROW(WebServer(o, nullptr).start(), std::runtime_error);
}

TEST(ViewerWebServer, ALateClientGetsTheNewestFrameOfEachTopic)
{
  WebServer server(test_options(), nullptr);
  server.start();
  server.publish("map", R"({"type":"map","version":1})");
  server.publish("map", R"({"type":"map","version":2})");
  Client c(server.port());
  EXPECT_EQ(c.next()["type"], "hello");
  EXPECT_EQ(c.next_of("map")["version"], 2);
}

TEST(ViewerWebServer, ASlowClientLosesFramesButNeverHoldsUpTheOthers)
{
  auto o = test_options();
  o.queue_frames = 12;
  WebServer server(o, nullptr);
  server.start();
  Client slow(server.port());   // never reads after this
  Client fast(server.port());
  EXPECT_EQ(fast.next()["type"], "hello");
  // 64 MB of frames, far more than the socket buffers hold for the slow client.
  const std::string filler(256 * 1024, 'x');
  constexpr int kFrames = 256;
  std::atomic<int> last_seen{-1};
  std::thread reader([&] {
    try {
      for (;;) {
        const json j = fast.next_of("scan");
        last_seen = j["seq"].get<int>();
        if (last_seen == kFrames - 1) break;
      }
    } catch (const std::exception&) {
    }
  });
  for (int i = 0; i < kFrames; ++i) server.publish("scan", json{{"type", "scan"}, {"seq", i}, {"filler", filler}}.dump());
  reader.join();
  EXPECT_EQ(last_seen.load(), kFrames - 1) << "the reading client got the newest frame";
  const auto stats = server.stats();
  EXPECT_GT(stats.frames_dropped, 0) << "the slow client's frames were dropped, not queued";
  EXPECT_EQ(stats.clients, 2);
}

TEST(ViewerWebServer, MalformedInputClosesThatClientOnly)
{
  auto o = test_options();
  o.max_input_bytes = 512;
  WebServer server(o, nullptr);
  server.start();
  Client good(server.port());
  EXPECT_EQ(good.next()["type"], "hello");
  for (int kind = 0; kind < 3; ++kind) {
    Client bad(server.port());
    EXPECT_EQ(bad.next()["type"], "hello");
    if (kind == 0) bad.ws.write(net::buffer(std::string("{\"type\":\"reboot\"}")));
    if (kind == 1) {
      bad.ws.binary(true);
      bad.ws.write(net::buffer(std::string("\x01\x02")));
    }
    if (kind == 2) bad.ws.write(net::buffer(std::string(4096, '{')));
    EXPECT_THROW(
        {
          for (int i = 0; i < 100; ++i) bad.next();
        },
        beast::system_error)
        << "kind " << kind;
  }
  server.publish("pose", R"({"type":"pose","seq":1})");
  EXPECT_EQ(good.next_of("pose")["seq"], 1);
  // Beast closes an oversized frame's connection itself, maybe before the count is taken.
  for (int i = 0; i < 200 && server.stats().closed_malformed < 3; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(server.stats().closed_malformed, 3);
}

TEST(ViewerWebServer, AGoalReachesTheHandlerAndIsAcknowledged)
{
  std::mutex m;
  std::vector<ClientGoal> goals;
  WebServer server(test_options(), [&](const ClientGoal& g) {
    std::lock_guard<std::mutex> lock(m);
    goals.push_back(g);
    return std::string();
  });
  server.start();
  Client c(server.port());
  c.ws.write(net::buffer(std::string(R"({"type":"goal","region_id":4})")));
  const json ack = c.next_of("goal_ack");
  EXPECT_TRUE(ack["ok"].get<bool>()) << ack.dump();
  std::lock_guard<std::mutex> lock(m);
  ASSERT_EQ(goals.size(), 1u);
  EXPECT_EQ(goals[0].request.region_id, 4);
  EXPECT_TRUE(goals[0].from_loopback);
}

TEST(ViewerWebServer, APageOfAnotherOriginCannotConnect)
{
  WebServer server(test_options(), nullptr);
  server.start();
  EXPECT_THROW(Client(server.port(), "http://evil.example"), beast::system_error);
  EXPECT_NO_THROW(Client(server.port(), "http://127.0.0.1:" + std::to_string(server.port())));
  EXPECT_EQ(server.stats().refused, 1);
}

TEST(ViewerWebServer, ClientsBeyondTheLimitAreRefused)
{
  auto o = test_options();
  o.max_clients = 2;
  WebServer server(o, nullptr);
  server.start();
  Client a(server.port()), b(server.port());
  EXPECT_EQ(a.next()["type"], "hello");
  EXPECT_EQ(b.next()["type"], "hello");
  EXPECT_THROW(Client(server.port()), beast::system_error);
  EXPECT_EQ(server.stats().refused, 1);
}

}  // namespace
}  // namespace rgnav::viewer
