// The message contract end to end, with real processes on real udpm multicast (inside a
// private network namespace, see tests/support/in_netns.sh):
//   C++ publisher --udpm--> C++ subscriber   (byte-identical, validated)
//                    \----> lcm-logger --> log --> lcm-logplayer --udpm--> C++ subscriber
//                                            \---> Java rgnav classes (lcm.logging.Log)
#include <gtest/gtest.h>
#include <lcm/lcm.h>
#include <sys/stat.h>

#include <csignal>
#include <fstream>
#include <thread>

#include "bus_watch.h"
#include "child_process.h"
#include "message_records.h"

namespace rgnav::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

const std::string kPrefix = "CONTRACT_";

std::vector<std::string> runtime_args(const std::string& program, const std::string& config)
{
  return {program, "--config", std::string(RGNAV_INTEGRATION_CONFIG_DIR) + "/" + config, "--lcm-url",
          test_udpm_url()};
}

struct LogEvent
{
  std::string channel;
  std::vector<uint8_t> data;
};

// Reads a log with liblcm's own reader; a truncated tail (logger killed mid-write) just ends it.
std::vector<LogEvent> read_log(const std::string& path)
{
  std::vector<LogEvent> out;
  lcm_eventlog_t* log = lcm_eventlog_create(path.c_str(), "r");
  if (!log) return out;
  while (lcm_eventlog_event_t* ev = lcm_eventlog_read_next_event(log)) {
    const auto* bytes = static_cast<const uint8_t*>(ev->data);
    out.push_back({std::string(ev->channel, static_cast<size_t>(ev->channellen)),
                   std::vector<uint8_t>(bytes, bytes + ev->datalen)});
    lcm_eventlog_free_event(ev);
  }
  lcm_eventlog_destroy(log);
  return out;
}

std::vector<LogEvent> contract_events(const std::vector<LogEvent>& events)
{
  std::vector<LogEvent> out;
  for (const auto& e : events)
    if (e.channel.rfind(kPrefix, 0) == 0) out.push_back(e);
  return out;
}

// Polls until pred() or timeout; true if pred() held.
template <class Pred>
bool eventually(milliseconds timeout, Pred pred)
{
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!pred()) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(milliseconds(20));
  }
  return true;
}

class Contract : public ::testing::Test
{
 protected:
  void SetUp() override { RGNAV_REQUIRE_NETNS(); }

  ChildOptions logged(const std::string& name) const
  {
    ChildOptions o;
    o.stderr_path = dir_.file(name + ".stderr");
    o.stdout_path = dir_.file(name + ".stdout");
    return o;
  }

  // Starts lcm-logger on the test URL. lcm-logger says nothing when it is ready, so callers wait
  // until a 5 Hz HEARTBEAT of some node shows up in the log before they publish.
  ChildProcess start_logger(const std::string& log_path)
  {
    ChildProcess logger({RGNAV_LCM_LOGGER, "-q", "-f", "--flush-interval=20", "--lcm-url=" + test_udpm_url(), log_path},
                        logged("lcm-logger"));
    return logger;
  }

  // Runs the publisher to completion; returns what it says it sent.
  std::vector<MessageRecord> publish(int rounds)
  {
    auto args = runtime_args(RGNAV_CONTRACT_PUBLISHER, "contract_publisher.yaml");
    args.insert(args.end(), {"--rounds", std::to_string(rounds), "--record", dir_.file("sent.tsv")});
    const auto status = run_to_completion(args, seconds(60), logged("publisher"));
    EXPECT_TRUE(status.clean()) << "publisher: " << status.describe() << "\n" << read_file(dir_.file("publisher.stderr"));
    return read_records(dir_.file("sent.tsv"));
  }

  // Logs `rounds` of the publisher's messages to log_path (a subscriber beaconing heartbeats
  // shows the logger is up first) and stops the logger once they are all in. `sent`: what the
  // publisher says it sent.
  void log_published(const std::string& log_path, int rounds, std::vector<MessageRecord>* sent)
  {
    HeartbeatWatch heartbeats(test_udpm_url());
    ChildProcess logger = start_logger(log_path);
    // The publisher's own heartbeats prove the logger is up only once it runs; use a subscriber
    // as the 5 Hz beacon.
    ChildProcess beacon(runtime_args(RGNAV_CONTRACT_SUBSCRIBER, "contract_subscriber.yaml"), logged("beacon"));
    ASSERT_TRUE(heartbeats.wait_for("contract_subscriber", seconds(20), beacon.pid()));
    ASSERT_TRUE(eventually(seconds(20), [&] { return !read_log(log_path).empty(); }));
    *sent = publish(rounds);
    ASSERT_TRUE(eventually(seconds(20), [&] { return contract_events(read_log(log_path)).size() >= sent->size(); }));
    logger.signal(SIGINT);
    ASSERT_TRUE(logger.wait_for(seconds(10)).has_value());
  }

  // Runs the Java check of the log against a record of what was sent.
  ExitStatus java_check(const std::string& log_path, const std::string& sent_tsv)
  {
    const std::string classpath = std::string(RGNAV_LCM_JAR) + ":" + RGNAV_TYPES_JAR + ":" + RGNAV_CHECK_JAR;
    return run_to_completion({RGNAV_JAVA, "-cp", classpath, "LogDecodeCheck", log_path, sent_tsv, kPrefix}, seconds(120),
                             logged("java"));
  }

  TempDir dir_{"rgnav_contract"};
};

TEST_F(Contract, UdpmLoggerAndReplayDeliverByteIdenticalMessages)
{
  const std::string log_path = dir_.file("contract.lcmlog");
  HeartbeatWatch heartbeats(test_udpm_url());

  ChildProcess logger = start_logger(log_path);
  auto sub_args = runtime_args(RGNAV_CONTRACT_SUBSCRIBER, "contract_subscriber.yaml");
  sub_args.insert(sub_args.end(), {"--record", dir_.file("live.tsv")});
  ChildProcess live_sub(sub_args, logged("live_subscriber"));
  ASSERT_TRUE(heartbeats.wait_for("contract_subscriber", seconds(20), live_sub.pid()))
      << "no heartbeat from the subscriber\n" << live_sub.stderr_text();
  ASSERT_TRUE(eventually(seconds(20), [&] { return !read_log(log_path).empty(); }))
      << "lcm-logger records nothing\n" << logger.stderr_text();

  const auto sent = publish(3);
  ASSERT_GT(sent.size(), 60u);

  // Live: the subscriber got every message, in order, with the bytes that were sent.
  ASSERT_TRUE(eventually(seconds(20), [&] { return read_records(dir_.file("live.tsv")).size() >= sent.size(); }))
      << "live subscriber received " << read_records(dir_.file("live.tsv")).size() << " of " << sent.size();
  EXPECT_EQ(read_records(dir_.file("live.tsv")), sent);

  // Log: lcm-logger recorded exactly those bytes.
  ASSERT_TRUE(eventually(seconds(20), [&] { return contract_events(read_log(log_path)).size() >= sent.size(); }));
  ASSERT_TRUE(logger.signal(SIGINT));
  const auto logger_exit = logger.wait_for(seconds(10));
  ASSERT_TRUE(logger_exit.has_value());
  EXPECT_TRUE(logger_exit->clean()) << logger_exit->describe();
  const auto events = contract_events(read_log(log_path));
  ASSERT_EQ(events.size(), sent.size());
  for (size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(events[i].channel, sent[i].channel) << i;
    EXPECT_EQ(to_hex(events[i].data.data(), events[i].data.size()), sent[i].hex) << i << " " << sent[i].channel;
  }

  const auto live_exit = live_sub.stop(seconds(10));
  EXPECT_TRUE(live_exit.clean()) << live_exit.describe() << "\n" << live_sub.stderr_text();

  // Replay: lcm-logplayer plays the log to a fresh subscriber, which gets the same bytes again.
  sub_args.back() = dir_.file("replay.tsv");
  ChildProcess replay_sub(sub_args, logged("replay_subscriber"));
  ASSERT_TRUE(heartbeats.wait_for("contract_subscriber", seconds(20), replay_sub.pid()));
  const auto player = run_to_completion({RGNAV_LCM_LOGPLAYER, "--lcm-url=" + test_udpm_url(), log_path}, seconds(60),
                                        logged("lcm-logplayer"));
  EXPECT_TRUE(player.clean()) << player.describe() << "\n" << read_file(dir_.file("lcm-logplayer.stderr"));
  ASSERT_TRUE(eventually(seconds(20), [&] { return read_records(dir_.file("replay.tsv")).size() >= sent.size(); }))
      << "replay subscriber received " << read_records(dir_.file("replay.tsv")).size() << " of " << sent.size();
  EXPECT_EQ(read_records(dir_.file("replay.tsv")), sent);
  const auto replay_exit = replay_sub.stop(seconds(10));
  EXPECT_TRUE(replay_exit.clean()) << replay_exit.describe();
}

TEST_F(Contract, JavaClassesDecodeALogWrittenFromCpp)
{
  const std::string log_path = dir_.file("java.lcmlog");
  std::vector<MessageRecord> sent;
  ASSERT_NO_FATAL_FAILURE(log_published(log_path, 2, &sent));
  const auto status = java_check(log_path, dir_.file("sent.tsv"));
  EXPECT_TRUE(status.clean()) << status.describe() << "\n"
                              << read_file(dir_.file("java.stderr")) << read_file(dir_.file("java.stdout"));
  EXPECT_NE(read_file(dir_.file("java.stdout")).find("OK: " + std::to_string(sent.size()) + " events"),
            std::string::npos)
      << read_file(dir_.file("java.stdout"));
}

TEST_F(Contract, JavaCheckFailsOnACorruptedRecord)
{
  // The Java check must be able to fail: change one value in what C++ claims it sent.
  const std::string log_path = dir_.file("java.lcmlog");
  std::vector<MessageRecord> sent;
  ASSERT_NO_FATAL_FAILURE(log_published(log_path, 1, &sent));

  // Same bytes, one JSON digit changed: only the field-by-field comparison can notice.
  auto& json = sent[sent.size() / 2].json;
  const auto digit = json.find_first_of("123456789");
  ASSERT_NE(digit, std::string::npos);
  json[digit] = json[digit] == '9' ? '1' : static_cast<char>(json[digit] + 1);
  {
    std::ofstream out(dir_.file("tampered.tsv"));
    for (const auto& r : sent) out << format_record(r) << '\n';
  }
  const auto status = java_check(log_path, dir_.file("tampered.tsv"));
  EXPECT_TRUE(status.exited && status.code == 1) << status.describe();
  EXPECT_NE(read_file(dir_.file("java.stderr")).find("field values differ"), std::string::npos)
      << read_file(dir_.file("java.stderr"));
}

}  // namespace
}  // namespace rgnav::testing
