// Validated configuration. One YAML file per process under config/; each algorithm reads its
// options struct from a Config section. Every key that is read is recorded, so finish() can
// refuse unknown keys (typos) — the message always names the file and the full key path.
//
//   auto cfg = config::Config::load("config/scan_mapper.yaml");
//   opts.max_range = cfg.section("matcher").number("max_range_m", 30.0, 1.0, 80.0);
//   cfg.finish();   // throws ConfigError: "config/scan_mapper.yaml: unknown key 'matcher.max_rnge_m'"
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace rgnav::config {

class ConfigError : public std::runtime_error
{
 public:
  using std::runtime_error::runtime_error;
};

class Config
{
 public:
  // Throws ConfigError if the file is missing, unreadable, empty or only comments, binary, not
  // YAML, or not a mapping (config/file_checks.h).
  static Config load(const std::string& path);
  // From YAML text (tests, embedded defaults); `origin` names it in messages.
  static Config parse(const std::string& yaml_text, const std::string& origin);

  // A sub-mapping. Missing sections read as empty (all defaults apply).
  Config section(const std::string& key) const;
  bool has(const std::string& key) const;
  // Keys of this mapping, in file order (for maps of user-named entries, e.g. worlds).
  std::vector<std::string> keys() const;

  double number(const std::string& key, double default_value, double min, double max) const;
  double required_number(const std::string& key, double min, double max) const;
  int64_t integer(const std::string& key, int64_t default_value, int64_t min, int64_t max) const;
  bool boolean(const std::string& key, bool default_value) const;
  std::string string(const std::string& key, const std::string& default_value) const;
  std::string required_string(const std::string& key) const;
  // One of `allowed`.
  std::string choice(const std::string& key, const std::string& default_value,
                     const std::vector<std::string>& allowed) const;
  // A sequence of numbers; size_min/size_max bound its length.
  std::vector<double> numbers(const std::string& key, const std::vector<double>& default_value,
                              double min, double max, size_t size_min = 0,
                              size_t size_max = SIZE_MAX) const;
  // A sequence of strings (a scalar counts as a list of one).
  std::vector<std::string> strings(const std::string& key, const std::vector<std::string>& default_value) const;
  // Elements of a sequence of mappings, each as a Config (e.g. walls of a world).
  std::vector<Config> list(const std::string& key) const;

  // Throws ConfigError listing every key in the file that nobody read.
  void finish() const;

  const std::string& origin() const { return state_->origin; }
  // "matcher.max_range_m" for key "max_range_m" in section "matcher".
  std::string path_of(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

 private:
  struct State
  {
    std::string origin;
    std::set<std::string> used;  // full key paths that were read
  };
  Config(std::shared_ptr<State> state, YAML::Node node, std::string prefix);
  YAML::Node lookup(const std::string& key) const;
  void collect_unknown(const YAML::Node& node, const std::string& prefix,
                       std::vector<std::string>* unknown) const;

  std::shared_ptr<State> state_;
  YAML::Node node_;
  std::string prefix_;
};

}  // namespace rgnav::config
