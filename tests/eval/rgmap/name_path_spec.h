// A benchmark's "NAME=PATH" argument (--sim office=config/worlds/office.yaml).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace rgnav::rgmap_pipeline {

inline std::pair<std::string, std::string> split_spec(const std::string& spec)
{
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0) throw std::runtime_error("expected NAME=PATH, got '" + spec + "'");
  return {spec.substr(0, eq), spec.substr(eq + 1)};
}

}  // namespace rgnav::rgmap_pipeline
