// Publish -> receive latency over udpm on loopback (run it inside a private network namespace:
// deploy/bench/lcm.sh does), for a 181-beam laser_scan_t and a ~1 MB stereo_images_t, through
// the rgnav runtime and through bare liblcm, in the same run.
//
// Processes: `run` (this process) is the sender and orchestrator; it starts two receiver
// processes of this same binary, `recv --mode runtime` (a runtime::Node with validated typed
// subscriptions) and `recv --mode raw` (lcm::LCM with lcm-gen typed handlers, no validation).
// The sender alternates runtime messages (runtime::Node::publish: checks + encode + publish)
// and raw ones (lcm::LCM::publish: encode + publish) on separate channels, so both paths see
// the same load and the same moment of the run. Both receivers get every datagram (one
// multicast group), so the cost of filtering the other path's channels is the same for both.
//
// Latency = receiver's CLOCK_MONOTONIC when its handler runs (after decode and, for the
// runtime, validation) minus the sender's CLOCK_MONOTONIC just before it started publishing,
// carried in the message's utime field (benchmark only: utime is not message time here).
#include <lcm/lcm-cpp.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <CLI/CLI.hpp>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <ctime>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "bus/typed.h"
#include "child_process.h"
#include "runtime/node.h"
#include "sample_messages.h"

namespace {

using namespace rgnav;
using Clock = std::chrono::steady_clock;

int64_t mono_ns()
{
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

const char* kRtLaser = "BENCH_RT_LASER";
const char* kRtImage = "BENCH_RT_IMAGE";
const char* kRawLaser = "BENCH_RAW_LASER";
const char* kRawImage = "BENCH_RAW_IMAGE";

struct Samples
{
  std::vector<int64_t> laser_ns;
  std::vector<int64_t> image_ns;
};

void write_samples(const std::string& path, const Samples& s)
{
  nlohmann::json j;
  j["laser_ns"] = s.laser_ns;
  j["image_ns"] = s.image_ns;
  std::ofstream(path) << j.dump();
}

void touch(const std::string& path) { std::ofstream(path) << "ready\n"; }

// ---- receivers -------------------------------------------------------------------------------

int receive_runtime(const std::string& url, const std::string& ready, const std::string& result, int lasers,
                    int images, int timeout_s)
{
  runtime::NodeOptions options;
  options.name = "bench_runtime_receiver";
  options.lcm_url = url;
  runtime::Node node(options);
  Samples s;
  s.laser_ns.reserve(static_cast<size_t>(lasers));
  auto done = [&] {
    if (static_cast<int>(s.laser_ns.size()) >= lasers && static_cast<int>(s.image_ns.size()) >= images)
      node.request_stop();
  };
  node.subscribe<laser_scan_t>(kRtLaser, [&](const laser_scan_t& m) {
    s.laser_ns.push_back(mono_ns() - m.utime);
    done();
  });
  node.subscribe<stereo_images_t>(kRtImage, [&](const stereo_images_t& m) {
    s.image_ns.push_back(mono_ns() - m.utime);
    done();
  });
  const auto deadline = Clock::now() + std::chrono::seconds(timeout_s);
  node.every(std::chrono::milliseconds(200), [&] {
    if (Clock::now() > deadline) node.request_stop();
  });
  touch(ready);
  node.run();
  write_samples(result, s);
  std::cerr << "runtime receiver: " << s.laser_ns.size() << " scans, " << s.image_ns.size() << " images, "
            << node.drops().total() << " dropped\n";
  return 0;
}

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_stop_signal(int) { g_stop = 1; }

class RawReceiver
{
 public:
  void on_laser(const lcm::ReceiveBuffer*, const std::string&, const laser_scan_t* m)
  {
    s.laser_ns.push_back(mono_ns() - m->utime);
  }
  void on_image(const lcm::ReceiveBuffer*, const std::string&, const stereo_images_t* m)
  {
    s.image_ns.push_back(mono_ns() - m->utime);
  }
  Samples s;
};

int receive_raw(const std::string& url, const std::string& ready, const std::string& result, int lasers, int images,
                int timeout_s)
{
  lcm::LCM lcm(url);
  if (!lcm.good()) {
    std::cerr << "raw receiver: cannot create LCM on " << url << "\n";
    return 1;
  }
  RawReceiver r;
  r.s.laser_ns.reserve(static_cast<size_t>(lasers));
  lcm.subscribe(kRawLaser, &RawReceiver::on_laser, &r);
  lcm.subscribe(kRawImage, &RawReceiver::on_image, &r);
  const auto deadline = Clock::now() + std::chrono::seconds(timeout_s);
  std::signal(SIGTERM, on_stop_signal);
  std::signal(SIGINT, on_stop_signal);
  touch(ready);
  while (!g_stop && (static_cast<int>(r.s.laser_ns.size()) < lasers || static_cast<int>(r.s.image_ns.size()) < images) &&
         Clock::now() < deadline)
    lcm.handleTimeout(100);
  write_samples(result, r.s);
  std::cerr << "raw receiver: " << r.s.laser_ns.size() << " scans, " << r.s.image_ns.size() << " images\n";
  return 0;
}

// ---- sender / orchestrator -------------------------------------------------------------------

double percentile_us(std::vector<int64_t> ns, double p)
{
  // Nearest-rank percentile.
  if (ns.empty()) return std::nan("");
  std::sort(ns.begin(), ns.end());
  const auto rank = static_cast<int64_t>(std::ceil(p / 100.0 * static_cast<double>(ns.size())));
  const auto k = static_cast<size_t>(std::clamp<int64_t>(rank - 1, 0, static_cast<int64_t>(ns.size()) - 1));
  return static_cast<double>(ns[k]) / 1000.0;
}

double round2(double v) { return std::round(v * 100.0) / 100.0; }

// In-process cost of the runtime's checks, per message (no network): validated bus::decode
// versus lcm-gen's decode, and validated bus::encode versus lcm-gen's encode.
template <class T>
nlohmann::json codec_costs(const T& msg, int iterations)
{
  std::vector<uint8_t> buf;
  std::string why;
  bus::encode(msg, &buf, &why);
  // Warm up first (the allocator settles: glibc raises its mmap threshold after the first large
  // free), then the median of 7 batches, so one descheduling on a busy machine does not count.
  auto time_us = [&](auto&& fn) {
    for (int i = 0; i < iterations / 4 + 1; ++i) fn();
    std::vector<double> batches;
    for (int b = 0; b < 7; ++b) {
      const auto t0 = Clock::now();
      for (int i = 0; i < iterations; ++i) fn();
      batches.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / iterations);
    }
    std::nth_element(batches.begin(), batches.begin() + 3, batches.end());
    return batches[3];
  };
  volatile int sink = 0;
  const double raw_decode = time_us([&] {
    T m;
    sink = sink + m.decode(buf.data(), 0, static_cast<int>(buf.size()));
  });
  const double rt_decode = time_us([&] {
    T m;
    sink = sink + bus::decode<T>(buf.data(), buf.size(), &m, &why);
  });
  const double raw_encode = time_us([&] {
    std::vector<uint8_t> out(static_cast<size_t>(msg.getEncodedSize()));
    sink = sink + msg.encode(out.data(), 0, static_cast<int>(out.size()));
  });
  const double rt_encode = time_us([&] {
    std::vector<uint8_t> out;
    sink = sink + bus::encode(msg, &out, &why);
  });
  return {{"bytes", buf.size()},
          {"lcm_decode_us", round2(raw_decode)},
          {"runtime_decode_us", round2(rt_decode)},
          {"lcm_encode_us", round2(raw_encode)},
          {"runtime_encode_us", round2(rt_encode)}};
}

struct RunOptions
{
  std::string url;
  std::string out;
  int lasers = 2000;
  int images = 100;
  int laser_gap_us = 2000;
  int image_gap_us = 25000;
};

int run(const RunOptions& o, const std::string& self)
{
  testing::TempDir dir("rgnav_bench_lcm");
  auto start = [&](const std::string& mode) {
    testing::ChildOptions co;
    co.stderr_path = dir.file(mode + ".stderr");
    co.stdout_path = dir.file(mode + ".stdout");  // spdlog's default logger writes to stdout
    return testing::ChildProcess({self, "recv", "--mode", mode, "--url", o.url, "--ready", dir.file(mode + ".ready"),
                                  "--result", dir.file(mode + ".json"), "--lasers", std::to_string(o.lasers),
                                  "--images", std::to_string(o.images), "--timeout-s", "120"},
                                 co);
  };
  testing::ChildProcess rt_rx = start("runtime");
  testing::ChildProcess raw_rx = start("raw");
  for (int i = 0; i < 2000 && (testing::read_file(dir.file("runtime.ready")).empty() ||
                               testing::read_file(dir.file("raw.ready")).empty());
       ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // let both join the group

  runtime::NodeOptions node_options;
  node_options.name = "bench_sender";
  node_options.lcm_url = o.url;
  runtime::Node node(node_options);
  lcm::LCM raw(o.url);
  if (!raw.good()) throw std::runtime_error("cannot create LCM on " + o.url);

  laser_scan_t scan = testing::sample_laser_scan(1, 181);
  stereo_images_t stereo = testing::sample_stereo(1, 720, 720, image_t::FORMAT_GRAY8);
  auto pace = [](Clock::time_point& next, int gap_us) {
    next += std::chrono::microseconds(gap_us);
    std::this_thread::sleep_until(next);
  };
  auto next = Clock::now();
  // Every message goes out twice, through the runtime node and through raw LCM, so both paths
  // carry the same load at the same pace; `id` is the message's own counter.
  auto send_both = [&](auto& m, auto& id, int count, int gap_us, const char* rt_channel, const char* raw_channel) {
    for (int i = 0; i < count; ++i) {
      ++id;
      m.utime = mono_ns();
      node.publish(rt_channel, m);
      pace(next, gap_us / 2);
      ++id;
      m.utime = mono_ns();
      raw.publish(raw_channel, &m);
      pace(next, gap_us / 2);
    }
  };
  send_both(scan, scan.scan_id, o.lasers, o.laser_gap_us, kRtLaser, kRawLaser);
  send_both(stereo, stereo.frame_id, o.images, o.image_gap_us, kRtImage, kRawImage);

  // Receivers exit once they have everything; what was lost they wait for until their timeout,
  // so give them a moment and then ask them to finish.
  for (auto* rx : {&rt_rx, &raw_rx}) {
    if (!rx->wait_for(std::chrono::seconds(3))) rx->signal(SIGTERM);
    const auto st = rx->wait_for(std::chrono::seconds(10));
    if (!st || !st->clean()) {
      std::cerr << rx->stderr_text();
      throw std::runtime_error("receiver failed: " + (st ? st->describe() : std::string("hung")));
    }
  }
  auto load = [&](const std::string& mode) {
    Samples s;
    const std::string text = testing::read_file(dir.file(mode + ".json"));
    if (text.empty()) return s;
    const auto j = nlohmann::json::parse(text);
    s.laser_ns = j["laser_ns"].get<std::vector<int64_t>>();
    s.image_ns = j["image_ns"].get<std::vector<int64_t>>();
    return s;
  };
  const Samples rt = load("runtime"), rw = load("raw");

  std::vector<uint8_t> scan_bytes, stereo_bytes;
  std::string why;
  bus::encode(scan, &scan_bytes, &why);
  bus::encode(stereo, &stereo_bytes, &why);
  const auto laser_codec = codec_costs(scan, 1000);
  const auto image_codec = codec_costs(stereo, 10);

  nlohmann::json j;
  j["runtime_p50_us"] = round2(percentile_us(rt.laser_ns, 50));
  j["runtime_p99_us"] = round2(percentile_us(rt.laser_ns, 99));
  j["raw_p50_us"] = round2(percentile_us(rw.laser_ns, 50));
  j["raw_p99_us"] = round2(percentile_us(rw.laser_ns, 99));
  j["image_runtime_p50_us"] = round2(percentile_us(rt.image_ns, 50));
  j["image_raw_p50_us"] = round2(percentile_us(rw.image_ns, 50));
  j["image_runtime_p99_us"] = round2(percentile_us(rt.image_ns, 99));
  j["image_raw_p99_us"] = round2(percentile_us(rw.image_ns, 99));
  j["laser_bytes"] = scan_bytes.size();
  j["image_bytes"] = stereo_bytes.size();
  j["laser_sent_per_path"] = o.lasers;
  j["image_sent_per_path"] = o.images;
  j["received"] = {{"runtime_laser", rt.laser_ns.size()}, {"raw_laser", rw.laser_ns.size()},
                   {"runtime_image", rt.image_ns.size()}, {"raw_image", rw.image_ns.size()}};
  j["codec_in_process"] = {{"laser_scan_t", laser_codec}, {"stereo_images_t", image_codec}};
  j["url"] = o.url;
  j["method"] =
      "three processes on one host in a private network namespace: a sender alternating runtime "
      "(runtime::Node::publish) and bare-LCM (lcm::LCM::publish) messages on separate channels, "
      "a runtime::Node receiver (validated typed subscribe) and an lcm::LCM receiver (lcm-gen "
      "typed handler); latency = receiver CLOCK_MONOTONIC in the handler - sender CLOCK_MONOTONIC "
      "before publish; laser every " + std::to_string(o.laser_gap_us) + " us, stereo every " +
      std::to_string(o.image_gap_us) + " us";
  const double d_laser = percentile_us(rt.laser_ns, 50) - percentile_us(rw.laser_ns, 50);
  const double d_image = percentile_us(rt.image_ns, 50) - percentile_us(rw.image_ns, 50);
  std::ostringstream notes;
  notes.precision(3);
  notes << "runtime minus bare LCM at p50: " << round2(d_laser) << " us for a 181-beam scan ("
        << scan_bytes.size() << " B), " << round2(d_image) << " us for a stereo pair (" << stereo_bytes.size()
        << " B). In process, validated decode costs " << laser_codec["runtime_decode_us"].get<double>()
        << " us vs " << laser_codec["lcm_decode_us"].get<double>() << " us (scan) and "
        << image_codec["runtime_decode_us"].get<double>() << " us vs " << image_codec["lcm_decode_us"].get<double>()
        << " us (stereo); validated encode " << laser_codec["runtime_encode_us"].get<double>() << " vs "
        << laser_codec["lcm_encode_us"].get<double>() << " us (scan), "
        << image_codec["runtime_encode_us"].get<double>() << " vs " << image_codec["lcm_encode_us"].get<double>()
        << " us (stereo). The rest of the end-to-end difference is the Node loop (poll on signalfd + LCM fd, "
           "timers) and run-to-run noise; compare with p99 and with repeated runs before reading much into "
           "differences of a few us.";
  j["notes"] = notes.str();

  std::ofstream(o.out) << j.dump(2) << "\n";
  std::cout << j.dump(2) << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"rgnav LCM latency benchmark (run inside a private network namespace)"};
  app.require_subcommand(1);
  RunOptions ro;
  ro.url = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608";
  auto* run_cmd = app.add_subcommand("run", "sender + orchestrator: starts the receivers, writes the JSON");
  run_cmd->add_option("--url", ro.url, "LCM URL");
  run_cmd->add_option("--out", ro.out, "result JSON")->required();
  run_cmd->add_option("--lasers", ro.lasers, "scans per path")->check(CLI::Range(10, 1000000));
  run_cmd->add_option("--images", ro.images, "stereo pairs per path")->check(CLI::Range(2, 100000));
  run_cmd->add_option("--laser-gap-us", ro.laser_gap_us)->check(CLI::Range(100, 1000000));
  run_cmd->add_option("--image-gap-us", ro.image_gap_us)->check(CLI::Range(1000, 10000000));

  std::string mode, url, ready, result;
  int lasers = 0, images = 0, timeout_s = 60;
  auto* recv_cmd = app.add_subcommand("recv", "receiver (started by run)");
  recv_cmd->add_option("--mode", mode)->required()->check(CLI::IsMember({"runtime", "raw"}));
  recv_cmd->add_option("--url", url)->required();
  recv_cmd->add_option("--ready", ready)->required();
  recv_cmd->add_option("--result", result)->required();
  recv_cmd->add_option("--lasers", lasers)->required();
  recv_cmd->add_option("--images", images)->required();
  recv_cmd->add_option("--timeout-s", timeout_s);
  CLI11_PARSE(app, argc, argv);

  try {
    if (*recv_cmd)
      return mode == "runtime" ? receive_runtime(url, ready, result, lasers, images, timeout_s)
                               : receive_raw(url, ready, result, lasers, images, timeout_s);
    return run(ro, std::filesystem::read_symlink("/proc/self/exe").string());
  } catch (const std::exception& e) {
    std::cerr << "rgnav_lcm_bench: " << e.what() << "\n";
    return 1;
  }
}
