#include "viewer/web_server.h"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "viewer/frame_queue.h"

namespace rgnav::viewer {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

namespace {

struct StaticFile
{
  std::string body;
  std::string mime;
};

std::string mime_of(const std::filesystem::path& p)
{
  const std::string ext = p.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".png") return "image/png";
  return "application/octet-stream";
}

// Requests are tiny (a GET of one of a few files): anything larger is not a page's.
constexpr size_t kMaxRequestBytes = 16 * 1024;
constexpr std::chrono::seconds kHttpTimeout{30};

}  // namespace

class WebServer::Impl
{
 public:
  class WsSession;
  class HttpSession;

  Impl(ServerOptions options, GoalHandler on_goal) : options_(std::move(options)), on_goal_(std::move(on_goal)) {}
  ~Impl() { stop(); }

  void start();
  void stop();
  void publish(const std::string& topic, std::string text);
  void do_accept();
  void add_session(uint64_t id, const std::shared_ptr<WsSession>& s);
  std::string handle_goal(uint64_t client, bool from_loopback, const GoalRequest& r);

  const ServerOptions options_;
  const GoalHandler on_goal_;
  std::map<std::string, StaticFile> files_;        // by request target ("/", "/viewer.js")
  std::atomic<uint16_t> port_{0};
  std::atomic<int64_t> clients_{0}, accepted_{0}, sent_{0}, dropped_{0}, malformed_{0}, refused_{0}, goals_{0};
  std::atomic<uint64_t> next_id_{1};
  // Server thread only:
  std::map<uint64_t, std::weak_ptr<WsSession>> sessions_;
  std::map<std::string, std::shared_ptr<const std::string>> latest_;
  std::thread thread_;
  bool running_ = false;
  // Last: destroyed first, with the handlers (and sessions) it still holds, while the counters
  // they update are alive. The acceptor is reset before.
  std::optional<tcp::acceptor> acceptor_;
  net::io_context ioc_{1};
};

// One page's WebSocket: a read loop for its goals and a write loop draining its queue.
class WebServer::Impl::WsSession : public std::enable_shared_from_this<WsSession>
{
 public:
  WsSession(Impl& server, uint64_t id, tcp::socket&& socket, bool loopback)
      : server_(server), id_(id), loopback_(loopback), ws_(std::move(socket)), queue_(server.options_.queue_frames)
  {
    ++server_.clients_;
  }
  ~WsSession()
  {
    --server_.clients_;
  }

  void run(http::request<http::string_body> req)
  {
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.read_message_max(server_.options_.max_input_bytes);
    ws_.async_accept(req, [self = shared_from_this()](beast::error_code ec) { self->on_accept(ec); });
  }

  void send(const std::string& topic, std::shared_ptr<const std::string> text)
  {
    if (closing_) return;
    const int64_t before = queue_.dropped();
    queue_.push({topic, std::move(text)});
    server_.dropped_ += queue_.dropped() - before;
    if (!writing_) write_next();
  }

 private:
  void on_accept(beast::error_code ec)
  {
    if (ec) return;
    server_.add_session(id_, shared_from_this());
    const std::string goals = loopback_ ? "allowed" : server_.options_.goal_token.empty() ? "off" : "token";
    send("hello", std::make_shared<const std::string>(nlohmann::json{{"type", "hello"}, {"client", id_}, {"goals", goals}}.dump()));
    for (const auto& [topic, text] : server_.latest_) send(topic, text);
    read_next();
  }

  void read_next()
  {
    ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, size_t) { self->on_read(ec); });
  }

  void on_read(beast::error_code ec)
  {
    if (ec) {
      // Too large a frame is the client's fault; a closed or broken connection is not.
      if (ec == websocket::error::message_too_big) close_malformed("frame too large");
      return;
    }
    if (!ws_.got_text()) return close_malformed("binary frame");
    const std::string text = beast::buffers_to_string(buffer_.data());
    buffer_.consume(buffer_.size());
    std::string why;
    const auto request = parse_client_input(text, &why);
    if (!request) return close_malformed(why);
    why = server_.handle_goal(id_, loopback_, *request);
    nlohmann::json ack{{"type", "goal_ack"}, {"ok", why.empty()}, {"why", why}, {"cancel", request->cancel}, {"region_id", request->region_id}};
    send("goal_ack", std::make_shared<const std::string>(ack.dump()));
    read_next();
  }

  void close_malformed(const std::string& why)
  {
    ++server_.malformed_;
    closing_ = true;
    websocket::close_reason reason(websocket::close_code::policy_error);
    reason.reason = why.substr(0, 100);   // a close frame's reason is at most 123 bytes
    ws_.async_close(reason, [self = shared_from_this()](beast::error_code) {});
  }

  void write_next()
  {
    auto frame = queue_.pop();
    if (!frame) {
      writing_ = false;
      return;
    }
    writing_ = true;
    ws_.text(true);
    auto text = frame->text;
    ws_.async_write(net::buffer(*text), [self = shared_from_this(), text](beast::error_code ec, size_t) {
      if (ec) {
        self->closing_ = true;
        return;
      }
      ++self->server_.sent_;
      if (!self->closing_) self->write_next();
    });
  }

  Impl& server_;
  const uint64_t id_;
  const bool loopback_;
  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  FrameQueue queue_;
  bool writing_ = false;
  bool closing_ = false;
};

// A plain HTTP connection: GET of the page's files, or the upgrade to a WebSocket at /ws.
class WebServer::Impl::HttpSession : public std::enable_shared_from_this<HttpSession>
{
 public:
  HttpSession(Impl& server, tcp::socket&& socket) : server_(server), stream_(std::move(socket)) {}

  void read_next()
  {
    parser_.emplace();
    parser_->header_limit(kMaxRequestBytes);
    parser_->body_limit(kMaxRequestBytes);
    stream_.expires_after(kHttpTimeout);
    http::async_read(stream_, buffer_, *parser_,
                     [self = shared_from_this()](beast::error_code ec, size_t) { self->on_read(ec); });
  }

 private:
  void on_read(beast::error_code ec)
  {
    if (ec) return;   // closed, timed out or not HTTP: the connection just ends
    http::request<http::string_body> req = parser_->release();
    if (websocket::is_upgrade(req)) return upgrade(std::move(req));
    auto res = std::make_shared<http::response<http::string_body>>(respond(req));
    http::async_write(stream_, *res, [self = shared_from_this(), res](beast::error_code ec, size_t) {
      if (ec || res->need_eof()) {
        beast::error_code ignored;
        self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
        return;
      }
      self->read_next();
    });
  }

  http::response<http::string_body> respond(const http::request<http::string_body>& req) const
  {
    auto reply = [&](http::status status, std::string body, const std::string& mime) {
      http::response<http::string_body> res{status, req.version()};
      res.set(http::field::content_type, mime);
      res.set(http::field::cache_control, "no-store");
      res.keep_alive(req.keep_alive());
      res.body() = req.method() == http::verb::head ? "" : std::move(body);
      res.prepare_payload();
      return res;
    };
    if (req.method() != http::verb::get && req.method() != http::verb::head)
      return reply(http::status::method_not_allowed, "GET only\n", "text/plain");
    std::string target(req.target());
    if (const auto q = target.find('?'); q != std::string::npos) target.resize(q);
    const auto f = server_.files_.find(target);
    if (f == server_.files_.end()) return reply(http::status::not_found, "not found\n", "text/plain");
    return reply(http::status::ok, f->second.body, f->second.mime);
  }

  void upgrade(http::request<http::string_body> req)
  {
    std::string target(req.target());
    if (const auto q = target.find('?'); q != std::string::npos) target.resize(q);
    const std::string origin(req[http::field::origin]);
    const bool same_origin = origin.empty() || origin == "http://" + std::string(req[http::field::host]);
    if (target != "/ws" || !same_origin || server_.clients_.load() >= static_cast<int64_t>(server_.options_.max_clients)) {
      ++server_.refused_;
      auto res = std::make_shared<http::response<http::string_body>>(http::status::forbidden, req.version());
      res->body() = target != "/ws" ? "no WebSocket here\n" : !same_origin ? "cross-origin WebSocket refused\n" : "too many clients\n";
      res->keep_alive(false);
      res->prepare_payload();
      http::async_write(stream_, *res, [self = shared_from_this(), res](beast::error_code, size_t) {
        beast::error_code ignored;
        self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
      });
      return;
    }
    beast::error_code ec;
    const auto remote = stream_.socket().remote_endpoint(ec);
    const bool loopback = !ec && remote.address().is_loopback();
    stream_.expires_never();   // the WebSocket has its own timeouts
    ++server_.accepted_;
    std::make_shared<WsSession>(server_, server_.next_id_++, stream_.release_socket(), loopback)->run(std::move(req));
  }

  Impl& server_;
  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
};

void WebServer::Impl::start()
{
  namespace fs = std::filesystem;
  std::error_code fec;
  if (!fs::is_directory(options_.web_root, fec))
    throw std::runtime_error("viewer: web root " + options_.web_root + " is not a folder");
  for (const auto& entry : fs::directory_iterator(options_.web_root)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream body;
    body << in.rdbuf();
    files_["/" + entry.path().filename().string()] = {body.str(), mime_of(entry.path())};
  }
  const auto index = files_.find("/index.html");
  if (index == files_.end()) throw std::runtime_error("viewer: no index.html in " + options_.web_root);
  files_["/"] = index->second;

  boost::system::error_code ec;
  const auto address = net::ip::make_address(options_.address, ec);
  if (ec) throw std::runtime_error("viewer: listen address '" + options_.address + "' is not an IP address");
  const tcp::endpoint endpoint(address, options_.port);
  acceptor_.emplace(ioc_);
  acceptor_->open(endpoint.protocol(), ec);
  if (!ec) acceptor_->set_option(net::socket_base::reuse_address(true), ec);
  if (!ec) acceptor_->bind(endpoint, ec);
  if (!ec) acceptor_->listen(net::socket_base::max_listen_connections, ec);
  if (ec)
    throw std::runtime_error("viewer: cannot listen on " + options_.address + ":" + std::to_string(options_.port) + ": " + ec.message());
  port_ = acceptor_->local_endpoint().port();
  do_accept();
  running_ = true;
  thread_ = std::thread([this] { ioc_.run(); });
}

void WebServer::Impl::stop()
{
  if (!running_) return;
  running_ = false;
  ioc_.stop();
  if (thread_.joinable()) thread_.join();
  boost::system::error_code ignored;
  if (acceptor_) acceptor_->close(ignored);
}

void WebServer::Impl::do_accept()
{
  acceptor_->async_accept([this](beast::error_code ec, tcp::socket socket) {
    if (!ec) std::make_shared<HttpSession>(*this, std::move(socket))->read_next();
    if (acceptor_->is_open()) do_accept();
  });
}

void WebServer::Impl::add_session(uint64_t id, const std::shared_ptr<WsSession>& s)
{
  for (auto it = sessions_.begin(); it != sessions_.end();) it = it->second.expired() ? sessions_.erase(it) : std::next(it);
  sessions_[id] = s;
}

void WebServer::Impl::publish(const std::string& topic, std::string text)
{
  auto frame = std::make_shared<const std::string>(std::move(text));
  net::post(ioc_, [this, topic, frame] {
    latest_[topic] = frame;
    for (auto it = sessions_.begin(); it != sessions_.end();) {
      if (auto s = it->second.lock()) {
        s->send(topic, frame);
        ++it;
      } else {
        it = sessions_.erase(it);
      }
    }
  });
}

std::string WebServer::Impl::handle_goal(uint64_t client, bool from_loopback, const GoalRequest& r)
{
  std::string why;
  if (!goal_allowed(r, from_loopback, options_.goal_token, &why)) return why;
  ++goals_;
  return on_goal_ ? on_goal_(ClientGoal{client, from_loopback, r}) : "goals are not taken here";
}

WebServer::WebServer(ServerOptions options, GoalHandler on_goal)
    : impl_(std::make_unique<Impl>(std::move(options), std::move(on_goal)))
{
}

WebServer::~WebServer() = default;

void WebServer::start() { impl_->start(); }
void WebServer::stop() { impl_->stop(); }
uint16_t WebServer::port() const { return impl_->port_.load(); }
void WebServer::publish(const std::string& topic, std::string text) { impl_->publish(topic, std::move(text)); }

ServerStats WebServer::stats() const
{
  ServerStats s;
  s.clients = impl_->clients_;
  s.accepted = impl_->accepted_;
  s.frames_sent = impl_->sent_;
  s.frames_dropped = impl_->dropped_;
  s.closed_malformed = impl_->malformed_;
  s.refused = impl_->refused_;
  s.goals = impl_->goals_;
  return s;
}

}  // namespace rgnav::viewer
