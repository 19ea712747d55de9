#include "explorer/explorer_state.h"

#include <stdexcept>

#include "persist/json_state.h"

namespace rgnav::explorer {

namespace {
constexpr const char* kSchema = "rgnav.explorer_state";
constexpr int kSchemaVersion = 1;
}  // namespace

void save_explorer_state(const std::string& path, const ExplorerState& s)
{
  persist::write_json_state(path, kSchema, kSchemaVersion, {{"utime", s.utime}, {"explorer", s.explorer}});
}

std::optional<ExplorerState> load_explorer_state(const std::string& path)
{
  const auto doc = persist::read_json_state(path, kSchema, kSchemaVersion, "an explorer");
  if (!doc) return std::nullopt;
  try {
    ExplorerState s;
    s.utime = doc->at("utime").get<int64_t>();
    if (s.utime < 0) throw std::invalid_argument("utime < 0");
    s.explorer = doc->at("explorer");
    if (!s.explorer.is_object()) throw std::invalid_argument("explorer is not an object");
    return s;
  } catch (const std::exception& e) {
    throw persist::not_this_state(path, "an explorer", e);
  }
}

}  // namespace rgnav::explorer
