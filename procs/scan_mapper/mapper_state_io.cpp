#include "scan_mapper/mapper_state_io.h"

#include <cstring>

#include "persist/atomic_file.h"
#include "scan_mapper/state_codec.h"

namespace rgnav::scan_mapper {
namespace {

constexpr char kMagic[8] = {'R', 'G', 'N', 'S', 'M', 'A', 'P', '2'};
constexpr uint32_t kVersion = 2;

}  // namespace

std::string encode_snapshot(const PersistedState& s)
{
  check_finite(s.mapper);
  persist::ByteWriter w;
  for (char c : kMagic) w.put(c);
  w.put(kVersion);
  w.put(s.last_record);
  w.put(s.ids.last_laser_id), w.put(s.ids.offset), w.put(s.ids.last_issued);
  w.put(static_cast<uint64_t>(s.mapper.nodes.size()));
  for (const auto& n : s.mapper.nodes) write_node(w, n);
  w.put(static_cast<uint64_t>(s.mapper.edges.size()));
  for (const auto& e : s.mapper.edges) write_edge(w, e);
  return w.take();
}

PersistedState decode_snapshot(const std::string& bytes)
{
  persist::ByteReader r(bytes);
  char magic[sizeof kMagic];
  for (char& c : magic) c = r.get<char>();
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) throw persist::CorruptBytes("not a scan mapper snapshot");
  const auto version = r.get<uint32_t>();
  if (version != kVersion) throw persist::CorruptBytes("unsupported snapshot version " + std::to_string(version));
  PersistedState s;
  s.last_record = r.get<uint64_t>();
  s.ids.last_laser_id = r.get<int64_t>();
  s.ids.offset = r.get<int64_t>();
  s.ids.last_issued = r.get<int64_t>();
  const uint64_t nn = r.count(1, 10'000'000);
  s.mapper.nodes.reserve(nn);
  for (uint64_t i = 0; i < nn; ++i) s.mapper.nodes.push_back(read_node(r));
  const uint64_t ne = r.count(1, 100'000'000);
  s.mapper.edges.reserve(ne);
  for (uint64_t i = 0; i < ne; ++i) s.mapper.edges.push_back(read_edge(r, nn));
  if (!r.at_end()) throw persist::CorruptBytes("trailing data");
  return s;
}

void save_snapshot(const PersistedState& state, const std::string& path)
{
  persist::write_atomically(path, encode_snapshot(state));
}

std::optional<PersistedState> load_snapshot(const std::string& path)
{
  const auto bytes = persist::read_checked(path);  // throws persist::CorruptFile
  if (!bytes) return std::nullopt;
  try {
    return decode_snapshot(*bytes);
  } catch (const persist::CorruptBytes& e) {
    throw persist::CorruptBytes(path + ": " + e.what());
  }
}

void save_state(const MapperState& state, const std::string& path) { save_snapshot({state, {}, 0}, path); }

std::optional<MapperState> load_state(const std::string& path)
{
  auto s = load_snapshot(path);
  if (!s) return std::nullopt;
  return std::move(s->mapper);
}

}  // namespace rgnav::scan_mapper
