#include "persist/json_state.h"

#include <filesystem>
#include <stdexcept>

#include "persist/checked_json.h"

namespace rgnav::persist {

void write_json_state(const std::string& path, const std::string& schema, int version, nlohmann::json body)
{
  body["schema"] = schema;
  body["schema_version"] = version;
  const auto dir = std::filesystem::path(path).parent_path();
  if (!dir.empty()) std::filesystem::create_directories(dir);
  write_json_atomically(path, std::move(body));
}

std::optional<nlohmann::json> read_json_state(const std::string& path, const std::string& schema, int version,
                                              const std::string& what)
{
  std::optional<nlohmann::json> doc;
  try {
    doc = read_checked_json(path);
  } catch (const std::exception& e) {
    throw std::runtime_error(e.what());   // CorruptFile names the file and the defect
  }
  if (!doc) return std::nullopt;
  try {
    auto& j = *doc;
    if (j.at("schema").get<std::string>() != schema) throw std::invalid_argument("schema is not " + schema);
    if (j.at("schema_version").get<int>() != version) throw std::invalid_argument("unknown schema_version");
    return doc;
  } catch (const std::exception& e) {
    throw not_this_state(path, what, e);
  }
}

std::runtime_error not_this_state(const std::string& path, const std::string& what, const std::exception& why)
{
  return std::runtime_error(path + ": not " + what + " state: " + why.what());
}

}  // namespace rgnav::persist
