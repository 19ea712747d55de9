#include "launch_plan.h"

#include <unistd.h>
#include <wordexp.h>

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <map>
#include <set>
#include <sstream>

namespace rgnav::supervisor {

const PlannedCommand* LaunchPlan::find(const std::string& name) const
{
  for (const auto& c : commands)
    if (c.spec.name == name) return &c;
  return nullptr;
}

std::vector<std::string> split_exec(const std::string& exec, const SourceLocation& where)
{
  wordexp_t we{};
  const int rc = wordexp(exec.c_str(), &we, WRDE_NOCMD | WRDE_UNDEF);
  if (rc != 0) {
    if (rc == 0 || rc == WRDE_NOSPACE) wordfree(&we);
    const char* why = rc == WRDE_BADVAL    ? "undefined variable"
                      : rc == WRDE_CMDSUB  ? "command substitution is not allowed"
                      : rc == WRDE_BADCHAR ? "unquoted | & ; < > ( ) { } or newline"
                      : rc == WRDE_SYNTAX  ? "syntax error (unbalanced quotes?)"
                                           : "cannot expand";
    throw LaunchError(where.str() + ": exec \"" + exec + "\": " + why);
  }
  std::vector<std::string> argv(we.we_wordv, we.we_wordv + we.we_wordc);
  wordfree(&we);
  if (argv.empty()) throw LaunchError(where.str() + ": exec is empty");
  return argv;
}

namespace {

bool executable(const std::string& path) { return access(path.c_str(), X_OK) == 0; }

std::string resolve_executable(const std::string& name, const PlanOptions& options)
{
  if (name.find('/') != std::string::npos) {
    const std::string p = name[0] == '/' ? name : options.root + "/" + name;
    return executable(p) ? p : "";
  }
  if (!options.bin_dir.empty() && executable(options.bin_dir + "/" + name)) return options.bin_dir + "/" + name;
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':'))
    if (!dir.empty() && executable(dir + "/" + name)) return dir + "/" + name;
  return "";
}

}  // namespace

LaunchPlan make_plan(const LaunchConfig& config, const PlanOptions& options)
{
  std::vector<std::string> errors;
  LaunchPlan plan;
  plan.config = config;

  std::map<std::string, const CommandSpec*> by_name;
  for (const auto& c : config.commands) {
    auto [it, fresh] = by_name.emplace(c.name, &c);
    if (!fresh) errors.push_back(c.where.str() + ": duplicate command name \"" + c.name + "\" (first at " + it->second->where.str() + ")");
    if (config.has_group(c.name))
      errors.push_back(c.where.str() + ": \"" + c.name + "\" names both a command and a group; orders would be ambiguous");
  }
  for (const auto& c : config.commands) {
    for (const auto& d : c.depends) {
      if (!by_name.count(d)) errors.push_back(c.where.str() + ": command \"" + c.name + "\" depends on unknown process \"" + d + "\"");
    }
  }

  // Cycles: depth-first search, reporting each cycle once as a path.
  std::map<std::string, int> mark;  // 0 new, 1 on stack, 2 done
  std::vector<std::string> stack;
  std::vector<const CommandSpec*> order;
  std::function<void(const CommandSpec&)> visit = [&](const CommandSpec& c) {
    mark[c.name] = 1;
    stack.push_back(c.name);
    for (const auto& d : c.depends) {
      auto it = by_name.find(d);
      if (it == by_name.end()) continue;
      if (mark[d] == 1) {
        std::string path;
        for (auto s = std::find(stack.begin(), stack.end(), d); s != stack.end(); ++s) path += *s + " -> ";
        errors.push_back(c.where.str() + ": dependency cycle: " + path + d);
      } else if (mark[d] == 0) {
        visit(*it->second);
      }
    }
    stack.pop_back();
    mark[c.name] = 2;
    order.push_back(&c);
  };
  std::set<std::string> seen;
  for (const auto& c : config.commands)
    if (mark[c.name] == 0 && seen.insert(c.name).second) visit(c);

  std::set<std::string> scripts;
  for (const auto& s : config.scripts)
    if (!scripts.insert(s.name).second) errors.push_back(s.where.str() + ": duplicate script name \"" + s.name + "\"");
  for (const auto& s : config.scripts) {
    for (const auto& a : s.actions) {
      if (a.kind == ScriptAction::Kind::kRunScript) {
        if (!scripts.count(a.ident)) errors.push_back(a.where.str() + ": script \"" + s.name + "\" runs unknown script \"" + a.ident + "\"");
      } else if (a.kind != ScriptAction::Kind::kWaitMs && a.target == ScriptAction::Target::kCommand) {
        if (!by_name.count(a.ident)) errors.push_back(a.where.str() + ": script \"" + s.name + "\" names unknown process \"" + a.ident + "\"");
      } else if (a.kind != ScriptAction::Kind::kWaitMs && a.target == ScriptAction::Target::kGroup) {
        if (!config.has_group(a.ident)) errors.push_back(a.where.str() + ": script \"" + s.name + "\" names unknown group \"" + a.ident + "\"");
      }
    }
  }

  for (const CommandSpec* c : order) {
    if (by_name[c->name] != c) continue;  // duplicate, already reported
    PlannedCommand pc;
    pc.spec = *c;
    try {
      pc.argv = split_exec(c->exec, c->exec_where);
    } catch (const LaunchError& e) {
      errors.push_back(e.what());
      continue;
    }
    pc.executable = resolve_executable(pc.argv[0], options);
    if (pc.executable.empty()) {
      if (options.allow_missing_executables) {
        plan.missing.push_back(c->name);
      } else {
        errors.push_back(c->exec_where.str() + ": missing executable \"" + pc.argv[0] + "\" for command \"" + c->name + "\"");
      }
    }
    if (!c->config.empty()) {
      // ${VAR} in the path: a test or a deployment points a command at a generated config.
      std::string expanded;
      try {
        const auto words = split_exec(c->config, c->where);
        if (words.size() != 1) throw LaunchError(c->where.str() + ": config \"" + c->config + "\" is not one path");
        expanded = words[0];
      } catch (const LaunchError& e) {
        errors.push_back(e.what());
        continue;
      }
      const std::string path = expanded[0] == '/' ? expanded : options.root + "/" + expanded;
      // A process not built yet (allowed missing) may not have its config written yet either.
      if (!pc.executable.empty() && access(path.c_str(), R_OK) != 0) {
        errors.push_back(c->where.str() + ": command \"" + c->name + "\": config file \"" + c->config + "\" not found (looked at " + path + ")");
      }
      pc.argv.push_back("--config");
      pc.argv.push_back(path);
    }
    plan.commands.push_back(std::move(pc));
  }

  if (!errors.empty()) {
    std::string all = std::to_string(errors.size()) + " error(s) in launch config " + config.file + ":";
    for (const auto& e : errors) all += "\n  " + e;
    throw LaunchError(all);
  }
  return plan;
}

}  // namespace rgnav::supervisor
