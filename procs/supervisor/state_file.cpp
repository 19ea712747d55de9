#include "state_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>
#include <stdexcept>

#include "config/file_checks.h"

namespace rgnav::supervisor {

SupervisorState load_state(const std::string& path)
{
  SupervisorState s;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return s;
  try {
    const auto j = nlohmann::json::parse(config::read_text_file(path, "supervisor state"));
    s.host = j.value("host", "");
    s.launch_config = j.value("launch_config", "");
    for (const auto& c : j.at("children")) {
      ChildRecord r;
      r.name = c.at("name").get<std::string>();
      r.pid = c.at("pid").get<pid_t>();
      r.start_ticks = c.at("start_ticks").get<uint64_t>();
      r.argv = c.at("argv").get<std::vector<std::string>>();
      r.stop_signal = c.value("stop_signal", 15);
      r.restarts = c.value("restarts", 0);
      s.children.push_back(std::move(r));
    }
    if (j.contains("done")) s.done = j.at("done").get<std::vector<std::string>>();
  } catch (const std::exception& e) {
    // Kept for a look, out of the way of the next save; without it no child can be adopted,
    // so a successor starts every process afresh.
    const std::string aside = path + ".damaged";
    std::filesystem::rename(path, aside, ec);
    spdlog::error("supervisor state {} not used ({}), moved to {}: no child is adopted", path, e.what(), aside);
    return SupervisorState{};
  }
  return s;
}

void save_state(const std::string& path, const SupervisorState& state)
{
  nlohmann::json j;
  j["host"] = state.host;
  j["launch_config"] = state.launch_config;
  j["children"] = nlohmann::json::array();
  for (const auto& c : state.children) {
    j["children"].push_back({{"name", c.name},
                             {"pid", c.pid},
                             {"start_ticks", c.start_ticks},
                             {"argv", c.argv},
                             {"stop_signal", c.stop_signal},
                             {"restarts", c.restarts}});
  }
  j["done"] = state.done;
  const std::string text = j.dump(2) + "\n";
  const std::string tmp = path + ".tmp";
  const int fd = open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write " + tmp + ": " + std::strerror(errno));
  const bool ok = write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) && fsync(fd) == 0;
  close(fd);
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
}

}  // namespace rgnav::supervisor
