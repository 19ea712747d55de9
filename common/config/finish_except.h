// Unknown-key check for a tool that loads part of a process's config file. An offline tool or
// a benchmark reads a process's config/<process>.yaml through that process's own loaders, but
// only for its algorithm's options: the sections that configure the live process (its node,
// channels, persistence, ...) are checked when the process starts. finish_except() refuses
// unknown keys in every other section, as Config::finish does for the process, so a misspelt
// key cannot leave a tool or a benchmark silently on a default.
#pragma once

#include <string>
#include <vector>

#include "config/config.h"

namespace rgnav::config {

// Throws ConfigError naming the file and every key nobody read, outside the top-level sections
// `process_sections`.
void finish_except(const Config& cfg, const std::vector<std::string>& process_sections);

}  // namespace rgnav::config
