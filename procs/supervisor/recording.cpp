#include "recording.h"

#include <filesystem>
#include <sstream>

#include "child_process.h"
#include "runtime/process_main.h"

namespace rgnav::supervisor {

void add_recorder(LaunchConfig& config, const std::string& host, const std::string& dir, double split_mb,
                  const std::string& lcm_url)
{
  make_dirs(dir);
  CommandSpec c;
  c.name = "lcm_logger";
  c.group = "recording";
  c.host = host;
  std::ostringstream exec;
  exec << "lcm-logger -q";
  if (!lcm_url.empty()) exec << " --lcm-url='" << lcm_url << "'";
  if (split_mb > 0) exec << " -i --split-mb=" << split_mb;
  exec << " '" << std::filesystem::absolute(dir).string() << "/rgnav.lcmlog'";
  c.exec = exec.str();
  c.heartbeat = false;  // lcm-logger has no heartbeat: watched by its exit alone
  c.stop_signal = 2;
  c.stop_time_allowed_s = 3;
  c.where = {config.file, 0};
  c.exec_where = c.where;
  config.groups.push_back({"recording", c.where});
  config.commands.push_back(std::move(c));
}

std::map<std::string, std::string> launch_environment(const std::string& argv0)
{
  std::error_code ec;
  auto exe = std::filesystem::canonical("/proc/self/exe", ec);
  if (ec) exe = std::filesystem::absolute(argv0);
  // <build>/bin/supervisor
  const std::string build = exe.parent_path().parent_path().string();
  const std::string config_dir = runtime::default_config_dir();
  const std::string root = std::filesystem::path(config_dir).parent_path().string();
  return {{"RGNAV_ROOT", root}, {"RGNAV_BUILD", build}, {"RGNAV_CONFIG_DIR", config_dir}};
}

}  // namespace rgnav::supervisor
