#include "config/config.h"

#include <cmath>
#include <sstream>

#include "config/file_checks.h"

namespace rgnav::config {

namespace {

std::string describe(const YAML::Node& n)
{
  if (!n.IsDefined() || n.IsNull()) return "nothing";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a mapping";
  return "'" + n.Scalar() + "'";
}

std::string range_text(double lo, double hi)
{
  std::ostringstream s;
  s << "[" << lo << ", " << hi << "]";
  return s.str();
}

// Nothing but comments and white space (YAML would read it as an empty mapping).
bool only_comments(const std::string& text)
{
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const size_t at = line.find_first_not_of(" \t\r");
    if (at != std::string::npos && line[at] != '#') return false;
  }
  return true;
}

}  // namespace

Config::Config(std::shared_ptr<State> state, YAML::Node node, std::string prefix)
    : state_(std::move(state)), node_(std::move(node)), prefix_(std::move(prefix))
{}

Config Config::load(const std::string& path)
{
  // Empty, binary or comment-only files are refused: a parser would read each as "all
  // defaults" (or a scalar), and a file cut off inside its header comment is only comments.
  const std::string text = read_text_file(path, "config");
  if (only_comments(text)) throw ConfigError(path + ": no keys (the file holds only comments)");
  return parse(text, path);
}

Config Config::parse(const std::string& yaml_text, const std::string& origin)
{
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(origin + ": not valid YAML: " + e.what());
  }
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap()) throw ConfigError(origin + ": top level must be a mapping of keys");
  auto state = std::make_shared<State>();
  state->origin = origin;
  return Config(state, root, "");
}

std::string Config::path_of(const std::string& key) const
{
  return prefix_.empty() ? key : prefix_ + "." + key;
}

void Config::fail(const std::string& key, const std::string& what) const
{
  throw ConfigError(state_->origin + ": key '" + path_of(key) + "': " + what);
}

YAML::Node Config::lookup(const std::string& key) const
{
  state_->used.insert(path_of(key));
  if (!node_.IsMap()) return YAML::Node();
  const YAML::Node& map = node_;  // const operator[]: a missing key must not be inserted
  return map[key];
}

bool Config::has(const std::string& key) const
{
  if (!node_.IsMap()) return false;
  const YAML::Node& map = node_;
  const YAML::Node n = map[key];
  return n.IsDefined() && !n.IsNull();
}

std::vector<std::string> Config::keys() const
{
  std::vector<std::string> out;
  if (!node_.IsMap()) return out;
  for (const auto& kv : node_) out.push_back(kv.first.Scalar());
  return out;
}

Config Config::section(const std::string& key) const
{
  const YAML::Node n = lookup(key);
  if (n.IsDefined() && !n.IsNull() && !n.IsMap()) fail(key, "expected a mapping, got " + describe(n));
  // A missing section reads as an empty mapping: every key takes its default.
  if (!n.IsDefined() || n.IsNull()) return Config(state_, YAML::Node(YAML::NodeType::Map), path_of(key));
  return Config(state_, n, path_of(key));
}

double Config::number(const std::string& key, double default_value, double min, double max) const
{
  const YAML::Node n = lookup(key);
  if (!n.IsDefined() || n.IsNull()) return default_value;
  double v = 0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, v) || !std::isfinite(v))
    fail(key, "expected a number, got " + describe(n));
  if (v < min || v > max) fail(key, "value " + n.Scalar() + " outside " + range_text(min, max));
  return v;
}

double Config::required_number(const std::string& key, double min, double max) const
{
  if (!has(key)) fail(key, "required number missing");
  return number(key, 0.0, min, max);
}

int64_t Config::integer(const std::string& key, int64_t default_value, int64_t min, int64_t max) const
{
  const YAML::Node n = lookup(key);
  if (!n.IsDefined() || n.IsNull()) return default_value;
  int64_t v = 0;
  if (!n.IsScalar() || !YAML::convert<int64_t>::decode(n, v))
    fail(key, "expected an integer, got " + describe(n));
  if (v < min || v > max)
    fail(key, "value " + n.Scalar() + " outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  return v;
}

bool Config::boolean(const std::string& key, bool default_value) const
{
  const YAML::Node n = lookup(key);
  if (!n.IsDefined() || n.IsNull()) return default_value;
  bool v = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, v))
    fail(key, "expected true or false, got " + describe(n));
  return v;
}

std::string Config::string(const std::string& key, const std::string& default_value) const
{
  const YAML::Node n = lookup(key);
  if (!n.IsDefined() || n.IsNull()) return default_value;
  if (!n.IsScalar()) fail(key, "expected a string, got " + describe(n));
  return n.Scalar();
}

std::string Config::required_string(const std::string& key) const
{
  if (!has(key)) fail(key, "required string missing");
  return string(key, "");
}

std::string Config::choice(const std::string& key, const std::string& default_value,
                           const std::vector<std::string>& allowed) const
{
  const std::string v = string(key, default_value);
  for (const auto& a : allowed)
    if (a == v) return v;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  fail(key, "'" + v + "' is not one of: " + list);
}

std::vector<double> Config::numbers(const std::string& key, const std::vector<double>& default_value,
                                    double min, double max, size_t size_min, size_t size_max) const
{
  const YAML::Node n = lookup(key);
  if (!n.IsDefined() || n.IsNull()) return default_value;
  if (!n.IsSequence()) fail(key, "expected a list of numbers, got " + describe(n));
  if (n.size() < size_min || n.size() > size_max)
    fail(key, "expected between " + std::to_string(size_min) + " and " + std::to_string(size_max) +
                  " numbers, got " + std::to_string(n.size()));
  std::vector<double> out;
  for (size_t i = 0; i < n.size(); ++i) {
    double v = 0;
    if (!n[i].IsScalar() || !YAML::convert<double>::decode(n[i], v) || !std::isfinite(v))
      fail(key, "element " + std::to_string(i) + ": expected a number, got " + describe(n[i]));
    if (v < min || v > max)
      fail(key, "element " + std::to_string(i) + " = " + n[i].Scalar() + " outside " + range_text(min, max));
    out.push_back(v);
  }
  return out;
}

std::vector<std::string> Config::strings(const std::string& key, const std::vector<std::string>& default_value) const
{
  const YAML::Node n = lookup(key);
  if (!n.IsDefined() || n.IsNull()) return default_value;
  if (n.IsScalar()) return {n.Scalar()};
  if (!n.IsSequence()) fail(key, "expected a list of strings, got " + describe(n));
  std::vector<std::string> out;
  for (size_t i = 0; i < n.size(); ++i) {
    if (!n[i].IsScalar()) fail(key, "element " + std::to_string(i) + ": expected a string, got " + describe(n[i]));
    out.push_back(n[i].Scalar());
  }
  return out;
}

std::vector<Config> Config::list(const std::string& key) const
{
  const YAML::Node n = lookup(key);
  std::vector<Config> out;
  if (!n.IsDefined() || n.IsNull()) return out;
  if (!n.IsSequence()) fail(key, "expected a list, got " + describe(n));
  for (size_t i = 0; i < n.size(); ++i) {
    const std::string elem_prefix = path_of(key) + "[" + std::to_string(i) + "]";
    if (!n[i].IsMap()) throw ConfigError(state_->origin + ": key '" + elem_prefix + "': expected a mapping");
    out.push_back(Config(state_, n[i], elem_prefix));
  }
  return out;
}

void Config::collect_unknown(const YAML::Node& node, const std::string& prefix,
                             std::vector<std::string>* unknown) const
{
  if (node.IsMap()) {
    for (const auto& kv : node) {
      const std::string path = prefix.empty() ? kv.first.Scalar() : prefix + "." + kv.first.Scalar();
      if (!state_->used.count(path)) {
        unknown->push_back(path);
        continue;
      }
      collect_unknown(kv.second, path, unknown);
    }
  } else if (node.IsSequence()) {
    // Only sequences read through list() hold mappings whose keys are tracked.
    for (size_t i = 0; i < node.size(); ++i)
      if (node[i].IsMap()) collect_unknown(node[i], prefix + "[" + std::to_string(i) + "]", unknown);
  }
}

void Config::finish() const
{
  std::vector<std::string> unknown;
  collect_unknown(node_, prefix_, &unknown);
  if (unknown.empty()) return;
  std::string text;
  for (const auto& u : unknown) text += (text.empty() ? "'" : ", '") + u + "'";
  throw ConfigError(state_->origin + ": unknown key" + (unknown.size() > 1 ? "s " : " ") + text);
}

}  // namespace rgnav::config
