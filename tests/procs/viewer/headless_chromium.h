// Headless Chromium driven over the DevTools protocol, for the viewer's browser test: the page's
// state is read with Runtime.evaluate whenever the test wants it (no race against a fixed
// virtual-time budget), a screenshot is taken with Page.captureScreenshot, a click is a real
// Input.dispatchMouseEvent. Header-only, test use only.
#pragma once

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "child_process.h"

namespace rgnav::testing {

class HeadlessChromium
{
 public:
  HeadlessChromium(const std::string& binary, const std::string& url, const std::filesystem::path& profile,
                   const std::string& log_path)
      : child_(
            {binary, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--user-data-dir=" + profile.string(),
             "--window-size=1200,800", "--remote-debugging-port=0", url},
            options(log_path))
  {
    // Chromium writes the port it picked into the profile.
    const auto port_file = profile / "DevToolsActivePort";
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    std::string port;
    while (port.empty()) {
      if (std::chrono::steady_clock::now() > deadline || !child_.running())
        throw std::runtime_error("chromium gave no DevTools port (see " + log_path + ")");
      std::ifstream in(port_file);
      std::getline(in, port);
      if (port.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    std::string ws_path;
    while (ws_path.empty()) {
      if (std::chrono::steady_clock::now() > deadline) throw std::runtime_error("chromium shows no page");
      for (const auto& t : nlohmann::json::parse(http_get(port, "/json/list"))) {
        if (t.value("type", "") == "page" && t.contains("webSocketDebuggerUrl")) {
          const std::string u = t["webSocketDebuggerUrl"];
          ws_path = u.substr(u.find('/', std::string("ws://").size()));
        }
      }
      if (ws_path.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    boost::asio::ip::tcp::resolver resolver(ioc_);
    boost::asio::connect(ws_.next_layer(), resolver.resolve("127.0.0.1", port));
    ws_.handshake("127.0.0.1:" + port, ws_path);
  }
  ~HeadlessChromium()
  {
    boost::beast::error_code ignored;
    ws_.next_layer().close(ignored);
    child_.stop(std::chrono::milliseconds(2000));
  }

  // The value of a JavaScript expression in the page (JSON-able).
  nlohmann::json evaluate(const std::string& expression)
  {
    const auto r = call("Runtime.evaluate", {{"expression", expression}, {"returnByValue", true}});
    return r["result"].value("value", nlohmann::json());
  }
  // A left click at viewport pixel (x, y).
  void click(double x, double y)
  {
    for (const char* type : {"mousePressed", "mouseReleased"})
      call("Input.dispatchMouseEvent", {{"type", type}, {"x", x}, {"y", y}, {"button", "left"}, {"clickCount", 1}});
  }
  // The page as PNG bytes.
  std::string screenshot_png() { return base64_decode(call("Page.captureScreenshot", {{"format", "png"}})["data"]); }

 private:
  static ChildOptions options(const std::string& log_path)
  {
    ChildOptions o;
    o.stdout_path = log_path;
    o.stderr_path = log_path;
    return o;
  }

  static std::string http_get(const std::string& port, const std::string& target)
  {
    namespace http = boost::beast::http;
    boost::asio::io_context ioc;
    boost::beast::tcp_stream stream(ioc);
    boost::asio::ip::tcp::resolver resolver(ioc);
    stream.connect(resolver.resolve("127.0.0.1", port));
    http::request<http::empty_body> req{http::verb::get, target, 11};
    req.set(http::field::host, "127.0.0.1:" + port);
    http::write(stream, req);
    boost::beast::flat_buffer b;
    http::response<http::string_body> res;
    http::read(stream, b, res);
    return res.body();
  }

  nlohmann::json call(const std::string& method, const nlohmann::json& params)
  {
    const int id = next_id_++;
    ws_.write(boost::asio::buffer(nlohmann::json{{"id", id}, {"method", method}, {"params", params}}.dump()));
    for (;;) {   // events may come first
      boost::beast::flat_buffer b;
      ws_.read(b);
      auto j = nlohmann::json::parse(boost::beast::buffers_to_string(b.data()));
      if (j.value("id", -1) != id) continue;
      if (j.contains("error")) throw std::runtime_error(method + ": " + j["error"].dump());
      return j["result"];
    }
  }

  static std::string base64_decode(const std::string& in)
  {
    static const std::string chars = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    int value = 0, bits = -8;
    for (char c : in) {
      const auto p = chars.find(c);
      if (p == std::string::npos) break;   // '=' padding
      value = ((value << 6) | static_cast<int>(p)) & 0xFFFFFF;   // only the bits not yet taken matter
      bits += 6;
      if (bits >= 0) {
        out.push_back(static_cast<char>((value >> bits) & 0xFF));
        bits -= 8;
      }
    }
    return out;
  }

  ChildProcess child_;
  boost::asio::io_context ioc_;
  boost::beast::websocket::stream<boost::asio::ip::tcp::socket> ws_{ioc_};
  int next_id_ = 1;
};

}  // namespace rgnav::testing
