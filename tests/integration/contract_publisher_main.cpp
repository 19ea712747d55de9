// Test-only rgnav process: publishes a sequence of varied messages of every message type, each
// on channel <prefix><type>, through the runtime (validated typed publish), and records what it
// sent (message_records.h format) so tests can compare it with what others received.
#include <CLI/CLI.hpp>

#include <fstream>

#include "bus/typed.h"
#include "message_records.h"
#include "rgnav_test_reflection.hpp"
#include "runtime/process_main.h"
#include "sample_messages.h"

namespace {

using namespace rgnav;

class ContractPublisher
{
 public:
  ContractPublisher(runtime::Node& node, const config::Config& cfg, int rounds, const std::string& record_path)
      : node_(node), prefix_(cfg.section("channels").string("prefix", "CONTRACT_")), rounds_(rounds),
        record_(record_path)
  {
    const auto contract = cfg.section("contract");
    const auto period = std::chrono::milliseconds(contract.integer("period_ms", 4, 1, 1000));
    const bool large = contract.boolean("large_stereo", true);
    if (!record_) throw std::runtime_error("cannot write " + record_path);
    for (int r = 0; r < rounds_; ++r) {
#define RGNAV_QUEUE(T) queue_.push_back([this, r] { send(#T, testing::sample<T>(static_cast<uint32_t>(r))); });
      RGNAV_FOR_EACH_MESSAGE_TYPE(RGNAV_QUEUE)
#undef RGNAV_QUEUE
      if (r == 0 && large)
        queue_.push_back([this] { send("stereo_images_t", testing::sample_stereo(1000, 720, 720, image_t::FORMAT_GRAY8)); });
    }
    node_.every(period, [this] { step(); });
  }

 private:
  template <class T>
  void send(const char* type, const T& msg)
  {
    const std::string channel = prefix_ + type;
    std::vector<uint8_t> bytes;
    std::string why;
    if (!bus::encode(msg, &bytes, &why)) throw std::runtime_error(std::string("sample not valid: ") + why);
    if (!node_.publish(channel, msg)) throw std::runtime_error("publish failed on " + channel);
    record_ << testing::format_record({channel, type, testing::to_hex(bytes.data(), bytes.size()), testing::to_json(msg)})
            << '\n';
    record_.flush();
  }

  void step()
  {
    if (next_ < queue_.size()) {
      queue_[next_++]();
      return;
    }
    spdlog::info("published {} messages", queue_.size());
    node_.request_stop();
  }

  runtime::Node& node_;
  std::string prefix_;
  int rounds_;
  std::ofstream record_;
  std::vector<std::function<void()>> queue_;
  size_t next_ = 0;
};

}  // namespace

int main(int argc, char** argv)
{
  int rounds = 2;
  std::string record_path = "/dev/null";
  return rgnav::runtime::process_main(
      argc, argv, "contract_publisher",
      [&](rgnav::runtime::ProcessContext& ctx) {
        return std::make_shared<ContractPublisher>(ctx.node, ctx.config, rounds, record_path);
      },
      [&](CLI::App& app) {
        app.add_option("--rounds", rounds, "rounds over all message types")->check(CLI::Range(1, 1000));
        app.add_option("--record", record_path, "file to write the sent messages to");
      });
}
