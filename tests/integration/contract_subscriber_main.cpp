// Test-only rgnav process: subscribes to every message type on <prefix><type> through the
// runtime (validated typed subscribe) and records each accepted message with the exact bytes
// received (message_records.h format), flushed per line so a test can poll the file.
#include <CLI/CLI.hpp>

#include <fstream>

#include "bus/typed.h"
#include "message_records.h"
#include "rgnav_test_reflection.hpp"
#include "runtime/process_main.h"

namespace {

using namespace rgnav;

class ContractSubscriber
{
 public:
  ContractSubscriber(runtime::Node& node, const config::Config& cfg, const std::string& record_path)
      : record_(record_path)
  {
    if (!record_) throw std::runtime_error("cannot write " + record_path);
    const std::string prefix = cfg.section("channels").string("prefix", "CONTRACT_");
#define RGNAV_SUBSCRIBE(T) listen<T>(node, prefix, #T);
    RGNAV_FOR_EACH_MESSAGE_TYPE(RGNAV_SUBSCRIBE)
#undef RGNAV_SUBSCRIBE
  }

 private:
  template <class T>
  void listen(runtime::Node& node, const std::string& prefix, const char* type)
  {
    // bus::subscribe (not Node::subscribe) because the record needs the raw received bytes;
    // validation and drop counting are the same.
    bus::subscribe<T>(
        node.bus(), prefix + type,
        [this, type](const T& msg, const bus::RawMessage& raw) {
          record_ << testing::format_record({raw.channel, type, testing::to_hex(raw.data, raw.size), testing::to_json(msg)})
                  << '\n';
          record_.flush();
        },
        &node.drops());
  }

  std::ofstream record_;
};

}  // namespace

int main(int argc, char** argv)
{
  std::string record_path = "/dev/null";
  return rgnav::runtime::process_main(
      argc, argv, "contract_subscriber",
      [&](rgnav::runtime::ProcessContext& ctx) {
        return std::make_shared<ContractSubscriber>(ctx.node, ctx.config, record_path);
      },
      [&](CLI::App& app) { app.add_option("--record", record_path, "file to write received messages to"); });
}
