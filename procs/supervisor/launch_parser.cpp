#include "launch_parser.h"

#include <cctype>
#include <fstream>
#include <sstream>

#include "config/config.h"
#include "config/file_checks.h"

namespace rgnav::supervisor {

const CommandSpec* LaunchConfig::find(const std::string& name) const
{
  for (const auto& c : commands)
    if (c.name == name) return &c;
  return nullptr;
}

namespace {

bool group_matches(const std::string& cmd_group, const std::string& group)
{
  if (group.empty()) return false;
  if (cmd_group == group || cmd_group.rfind(group + "/", 0) == 0) return true;
  // A bare name matches that group at any depth ("vision" matches "perception/vision/...").
  if (group.find('/') != std::string::npos) return false;
  std::stringstream parts(cmd_group);
  std::string part;
  while (std::getline(parts, part, '/'))
    if (part == group) return true;
  return false;
}

}  // namespace

bool LaunchConfig::has_group(const std::string& path_or_name) const
{
  for (const auto& g : groups)
    if (group_matches(g.path, path_or_name)) return true;
  return false;
}

std::vector<const CommandSpec*> LaunchConfig::in_group(const std::string& group) const
{
  std::vector<const CommandSpec*> out;
  for (const auto& c : commands)
    if (group_matches(c.group, group)) out.push_back(&c);
  return out;
}

namespace {

enum class Tok { kIdent, kString, kInteger, kOpen, kClose, kAssign, kEnd, kEof };

struct Token
{
  Tok type = Tok::kEof;
  std::string text;
  int line = 0;
};

const char* tok_name(Tok t)
{
  switch (t) {
    case Tok::kIdent: return "identifier";
    case Tok::kString: return "string";
    case Tok::kInteger: return "integer";
    case Tok::kOpen: return "'{'";
    case Tok::kClose: return "'}'";
    case Tok::kAssign: return "'='";
    case Tok::kEnd: return "';'";
    case Tok::kEof: return "end of file";
  }
  return "?";
}

class Lexer
{
 public:
  Lexer(const std::string& text, std::string origin) : text_(text), origin_(std::move(origin)) {}

  Token next()
  {
    skip_space_and_comments();
    Token t;
    t.line = line_;
    if (pos_ >= text_.size()) return t;
    const char c = text_[pos_];
    if (c == '{' || c == '}' || c == '=' || c == ';') {
      ++pos_;
      t.type = c == '{' ? Tok::kOpen : c == '}' ? Tok::kClose : c == '=' ? Tok::kAssign : Tok::kEnd;
      t.text = std::string(1, c);
      return t;
    }
    if (c == '"') return string_token();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      t.type = Tok::kIdent;
      while (pos_ < text_.size() &&
             (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_' || text_[pos_] == '-'))
        t.text += text_[pos_++];
      return t;
    }
    if (std::isdigit(static_cast<unsigned char>(c))) {
      t.type = Tok::kInteger;
      while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) t.text += text_[pos_++];
      // rgnav extension: a fractional part (stop_time_allowed = 0.5;).
      if (pos_ + 1 < text_.size() && text_[pos_] == '.' && std::isdigit(static_cast<unsigned char>(text_[pos_ + 1]))) {
        t.text += text_[pos_++];
        while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) t.text += text_[pos_++];
      }
      return t;
    }
    throw LaunchError(origin_ + ":" + std::to_string(line_) + ": invalid character '" + std::string(1, c) + "'");
  }

 private:
  void skip_space_and_comments()
  {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++pos_;
      } else if (c == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else {
        return;
      }
    }
  }

  Token string_token()
  {
    Token t;
    t.type = Tok::kString;
    t.line = line_;
    ++pos_;  // opening quote
    while (true) {
      if (pos_ >= text_.size() || text_[pos_] == '\n')
        throw LaunchError(origin_ + ":" + std::to_string(t.line) + ": unterminated string constant");
      char c = text_[pos_++];
      if (c == '"') return t;
      if (c == '\\' && pos_ < text_.size()) {
        c = text_[pos_++];
        c = c == 'n' ? '\n' : c == 't' ? '\t' : c == 'r' ? '\r' : c;
      }
      t.text += c;
    }
  }

  const std::string& text_;
  std::string origin_;
  size_t pos_ = 0;
  int line_ = 1;
};

std::vector<std::string> split_list(const std::string& s)
{
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto b = item.find_first_not_of(" \t");
    const auto e = item.find_last_not_of(" \t");
    if (b != std::string::npos) out.push_back(item.substr(b, e - b + 1));
  }
  return out;
}

class Parser
{
 public:
  Parser(const std::string& text, const std::string& origin) : lexer_(text, origin), origin_(origin)
  {
    next_ = lexer_.next();
  }

  LaunchConfig parse()
  {
    LaunchConfig cfg;
    cfg.file = origin_;
    while (next_.type != Tok::kEof) {
      const Token kw = expect(Tok::kIdent, "'cmd', 'group' or 'script'");
      if (kw.text == "cmd") {
        parse_command(cfg, "", kw.line);
      } else if (kw.text == "group") {
        parse_group(cfg, "");
      } else if (kw.text == "script") {
        parse_script(cfg, kw.line);
      } else {
        fail(kw.line, "expected 'cmd', 'group' or 'script', got '" + kw.text + "'");
      }
    }
    return cfg;
  }

 private:
  [[noreturn]] void fail(int line, const std::string& what) const
  {
    throw LaunchError(origin_ + ":" + std::to_string(line) + ": " + what);
  }

  Token take()
  {
    Token t = next_;
    next_ = lexer_.next();
    return t;
  }

  bool eat(Tok type)
  {
    if (next_.type != type) return false;
    take();
    return true;
  }

  Token expect(Tok type, const std::string& what)
  {
    if (next_.type != type) {
      const std::string got = next_.type == Tok::kEof ? "end of file" : std::string(tok_name(next_.type)) + " '" + next_.text + "'";
      fail(next_.line, "expected " + what + ", got " + got);
    }
    return take();
  }

  void expect_word(const std::string& word)
  {
    const Token t = expect(Tok::kIdent, "'" + word + "'");
    if (t.text != word) fail(t.line, "expected '" + word + "', got '" + t.text + "'");
  }

  SourceLocation at(int line) const { return {origin_, line}; }

  void parse_group(LaunchConfig& cfg, const std::string& parent)
  {
    const Token name = expect(Tok::kString, "group name string");
    if (name.text.find('/') != std::string::npos) fail(name.line, "'/' is not allowed in group name");
    if (name.text.find_first_not_of(" \t") == std::string::npos) fail(name.line, "empty group name");
    const std::string path = parent.empty() ? name.text : parent + "/" + name.text;
    bool known = false;
    for (const auto& g : cfg.groups) known = known || g.path == path;
    if (!known) cfg.groups.push_back({path, at(name.line)});
    expect(Tok::kOpen, "'{'");
    while (next_.type == Tok::kIdent) {
      const Token kw = take();
      if (kw.text == "cmd") {
        parse_command(cfg, path, kw.line);
      } else if (kw.text == "group") {
        parse_group(cfg, path);
      } else {
        fail(kw.line, "expected 'cmd' or 'group' in group \"" + path + "\", got '" + kw.text + "'");
      }
    }
    expect(Tok::kClose, "'}' closing group \"" + path + "\"");
  }

  static bool parse_bool(const std::string& v, bool* out)
  {
    if (v == "true" || v == "1" || v == "yes") {
      *out = true;
      return true;
    }
    if (v == "false" || v == "0" || v == "no") {
      *out = false;
      return true;
    }
    return false;
  }

  // Numeric attributes accept procman's integer literal or a string holding a number.
  double number_value(const Token& name, const Token& value, double min, double max)
  {
    double v = 0;
    try {
      size_t used = 0;
      v = std::stod(value.text, &used);
      if (used != value.text.size()) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      fail(value.line, "attribute '" + name.text + "' needs a number, got \"" + value.text + "\"");
    }
    if (v < min || v > max)
      fail(value.line, "attribute '" + name.text + "' = " + value.text + " is outside [" + std::to_string(static_cast<int>(min)) +
                           ", " + std::to_string(static_cast<int>(max)) + "]");
    return v;
  }

  void parse_command(LaunchConfig& cfg, const std::string& group, int line)
  {
    CommandSpec cmd;
    cmd.group = group;
    cmd.where = at(line);
    bool named = false;
    if (next_.type == Tok::kString) {
      const Token name = take();
      if (name.text.find('/') != std::string::npos) fail(name.line, "'/' is not allowed in command name");
      cmd.name = name.text;
      named = true;
    }
    expect(Tok::kOpen, "'{'");
    bool has_exec = false;
    while (next_.type == Tok::kIdent) {
      const Token key = take();
      expect(Tok::kAssign, "'=' after '" + key.text + "'");
      if (next_.type != Tok::kString && next_.type != Tok::kInteger)
        fail(next_.line, "attribute '" + key.text + "' needs a string or integer value");
      const Token value = take();
      expect(Tok::kEnd, "';' after attribute '" + key.text + "'");
      const std::string& k = key.text;
      const std::string& v = value.text;
      if (k == "exec") {
        cmd.exec = v;
        cmd.exec_where = at(value.line);
        has_exec = !v.empty();
      } else if (k == "host") {
        cmd.host = v;
      } else if (k == "group") {
        // procman writes the group of a top-level command as an attribute.
        if (!group.empty() && v != group) fail(value.line, "group attribute \"" + v + "\" inside group \"" + group + "\"");
        cmd.group = v;
      } else if (k == "nickname") {
        cmd.name = v;
        named = true;
      } else if (k == "auto_respawn" || k == "heartbeat" || k == "safety_critical" || k == "oneshot") {
        bool b = false;
        if (!parse_bool(v, &b)) fail(value.line, "attribute '" + k + "' must be \"true\" or \"false\", got \"" + v + "\"");
        if (k == "auto_respawn") {
          cmd.auto_respawn = b;
          cmd.auto_respawn_set = true;
        } else if (k == "heartbeat") {
          cmd.heartbeat = b;
        } else if (k == "oneshot") {
          cmd.oneshot = b;
        } else {
          cmd.safety_critical = b;
        }
      } else if (k == "stop_signal") {
        cmd.stop_signal = static_cast<int>(number_value(key, value, 1, 64));
      } else if (k == "stop_time_allowed") {
        cmd.stop_time_allowed_s = number_value(key, value, 0.001, 3600);
      } else if (k == "heartbeat_timeout_ms") {
        cmd.heartbeat_timeout_ms = static_cast<int>(number_value(key, value, 50, 600000));
      } else if (k == "startup_timeout_ms") {
        cmd.startup_timeout_ms = static_cast<int>(number_value(key, value, 50, 600000));
      } else if (k == "work_timeout_ms") {
        cmd.work_timeout_ms = static_cast<int>(number_value(key, value, 50, 600000));
      } else if (k == "depends") {
        cmd.depends = split_list(v);
      } else if (k == "inputs") {
        cmd.inputs = split_list(v);
      } else if (k == "config") {
        cmd.config = v;
      } else if (k == "env") {
        for (const auto& kv : split_list(v)) {
          const auto eq = kv.find('=');
          if (eq == std::string::npos || eq == 0) fail(value.line, "env entry \"" + kv + "\" is not K=V");
          cmd.env.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
        }
      } else {
        fail(key.line, "unknown attribute '" + k + "'");
      }
    }
    expect(Tok::kClose, "'}' closing cmd");
    if (!has_exec) fail(line, "command " + (named ? "\"" + cmd.name + "\" " : std::string()) + "has no exec");
    if (!named) {
      // procman allows unnamed commands; their executable's name is the name.
      std::string first = cmd.exec.substr(0, cmd.exec.find(' '));
      cmd.name = first.substr(first.find_last_of('/') + 1);
    }
    if (cmd.name.empty()) fail(line, "command has an empty name");
    cfg.commands.push_back(std::move(cmd));
  }

  void parse_script(LaunchConfig& cfg, int line)
  {
    ScriptSpec script;
    script.where = at(line);
    script.name = expect(Tok::kString, "script name").text;
    expect(Tok::kOpen, "'{'");
    while (next_.type == Tok::kIdent) {
      const Token kw = take();
      ScriptAction a;
      a.where = at(kw.line);
      if (kw.text == "start" || kw.text == "stop" || kw.text == "restart") {
        a.kind = kw.text == "start" ? ScriptAction::Kind::kStart
                 : kw.text == "stop" ? ScriptAction::Kind::kStop
                                     : ScriptAction::Kind::kRestart;
        const Token what = expect(Tok::kIdent, "'everything', 'cmd' or 'group'");
        if (what.text == "everything") {
          a.target = ScriptAction::Target::kEverything;
        } else if (what.text == "cmd" || what.text == "group") {
          a.target = what.text == "cmd" ? ScriptAction::Target::kCommand : ScriptAction::Target::kGroup;
          a.ident = expect(Tok::kString, what.text + " name").text;
        } else {
          fail(what.line, "expected 'everything', 'cmd' or 'group', got '" + what.text + "'");
        }
        if (!eat(Tok::kEnd)) {
          expect_word("wait");
          a.wait_status = wait_status();
          expect(Tok::kEnd, "';'");
        }
      } else if (kw.text == "wait") {
        const Token what = expect(Tok::kIdent, "'ms', 'cmd' or 'group'");
        if (what.text == "ms") {
          a.kind = ScriptAction::Kind::kWaitMs;
          const Token ms = expect(Tok::kInteger, "a delay in milliseconds");
          if (ms.text.find('.') != std::string::npos) fail(ms.line, "wait ms needs a whole number of milliseconds");
          a.delay_ms = std::stoi(ms.text);
        } else if (what.text == "cmd" || what.text == "group") {
          a.kind = ScriptAction::Kind::kWaitStatus;
          a.target = what.text == "cmd" ? ScriptAction::Target::kCommand : ScriptAction::Target::kGroup;
          a.ident = expect(Tok::kString, what.text + " name").text;
          expect_word("status");
          a.wait_status = wait_status();
        } else {
          fail(what.line, "expected 'ms', 'cmd' or 'group' after 'wait', got '" + what.text + "'");
        }
        expect(Tok::kEnd, "';'");
      } else if (kw.text == "run_script") {
        a.kind = ScriptAction::Kind::kRunScript;
        a.ident = expect(Tok::kString, "script name").text;
        expect(Tok::kEnd, "';'");
      } else {
        fail(kw.line, "unexpected '" + kw.text + "' in script \"" + script.name + "\"");
      }
      script.actions.push_back(std::move(a));
    }
    expect(Tok::kClose, "'}' closing script");
    cfg.scripts.push_back(std::move(script));
  }

  std::string wait_status()
  {
    const Token s = expect(Tok::kString, "\"running\" or \"stopped\"");
    if (s.text != "running" && s.text != "stopped") fail(s.line, "expected \"running\" or \"stopped\", got \"" + s.text + "\"");
    return s.text;
  }

  Lexer lexer_;
  std::string origin_;
  Token next_;
};

}  // namespace

LaunchConfig parse_launch_text(const std::string& text, const std::string& origin)
{
  return Parser(text, origin).parse();
}

LaunchConfig parse_launch_file(const std::string& path)
{
  std::string text;
  try {
    text = config::read_text_file(path, "launch config");   // empty or binary: refused, named
  } catch (const config::ConfigError& e) {
    throw LaunchError(e.what());
  }
  LaunchConfig c = parse_launch_text(text, path);
  if (c.commands.empty()) throw LaunchError(path + ": no commands (a launch config cut off, or not one)");
  return c;
}

}  // namespace rgnav::supervisor
