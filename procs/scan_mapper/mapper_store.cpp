#include "scan_mapper/mapper_store.h"


#include <filesystem>
#include <optional>

#include "scan_mapper/state_codec.h"

namespace rgnav::scan_mapper {
namespace {

enum Tag : uint32_t { kScan = 1, kEstimates = 2 };

void write_ids(persist::ByteWriter& w, const ScanIdState& ids)
{
  w.put(ids.last_laser_id), w.put(ids.offset), w.put(ids.last_issued);
}

ScanIdState read_ids(persist::ByteReader& r)
{
  ScanIdState ids;
  ids.last_laser_id = r.get<int64_t>();
  ids.offset = r.get<int64_t>();
  ids.last_issued = r.get<int64_t>();
  return ids;
}

std::vector<PoseGraphEdge> read_new_edges(persist::ByteReader& r, uint64_t node_count)
{
  std::vector<PoseGraphEdge> edges(r.count(1, 1'000'000));
  for (auto& e : edges) e = read_edge(r, node_count);
  return edges;
}

// Applies one journal record to the state, all or nothing; throws persist::CorruptBytes (leaving the
// state untouched) if it does not fit.
void apply(const persist::JournalRecord& rec, PersistedState* st)
{
  persist::ByteReader r(rec.bytes);
  const auto seq = r.get<uint64_t>();
  if (seq != st->last_record + 1)
    throw persist::CorruptBytes("it follows record " + std::to_string(st->last_record));
  const ScanIdState ids = read_ids(r);
  auto& nodes = st->mapper.nodes;
  std::optional<ScanNode> added;
  std::vector<ScanNode> estimates;
  if (rec.tag == kScan) {
    const auto index = r.get<uint64_t>();
    if (index != nodes.size())
      throw persist::CorruptBytes("it adds node " + std::to_string(index) + " to a state of " +
                                  std::to_string(nodes.size()));
    added = read_node(r);
  } else if (rec.tag == kEstimates) {
    estimates.resize(r.count(1, nodes.size()));
    for (auto& e : estimates) read_estimate(r, &e);
  } else {
    throw persist::CorruptBytes("unknown record tag " + std::to_string(rec.tag));
  }
  auto edges = read_new_edges(r, nodes.size() + (added ? 1 : 0));
  if (!r.at_end()) throw persist::CorruptBytes("trailing bytes");
  if (added) nodes.push_back(std::move(*added));
  for (size_t i = 0; i < estimates.size(); ++i) {
    nodes[i].map_from_base = estimates[i].map_from_base;
    nodes[i].published = estimates[i].published;
    nodes[i].covariance = estimates[i].covariance;
    nodes[i].revision = estimates[i].revision;
  }
  st->mapper.edges.insert(st->mapper.edges.end(), edges.begin(), edges.end());
  st->ids = ids;
  st->last_record = seq;
}

}  // namespace

MapperStore::MapperStore(StoreOptions options) : options_(std::move(options))
{
  journal_ = std::make_unique<persist::Journal>(options_.snapshot_path + ".journal", options_.fsync_each_record);
  recover();
}

void MapperStore::recover()
{
  const auto keep_aside = [](const std::string& path) {
    std::error_code ec;
    if (std::filesystem::exists(path, ec)) std::filesystem::copy_file(path, path + ".corrupt", std::filesystem::copy_options::overwrite_existing, ec);
  };
  std::optional<PersistedState> snap;
  if (options_.resume) {
    try {
      snap = load_snapshot(options_.snapshot_path);
    } catch (const std::exception& e) {
      // The journal continues a snapshot we cannot read: both are kept for inspection and the
      // map starts afresh rather than from a guess.
      report_.damage = std::string("snapshot refused (") + e.what() + "); kept as .corrupt, starting afresh";
      keep_aside(options_.snapshot_path);
      keep_aside(options_.snapshot_path + ".journal");
    }
  }
  const bool fresh = !options_.resume || !report_.damage.empty();
  PersistedState st = snap ? std::move(*snap) : PersistedState{};
  report_.snapshot_scans = st.mapper.nodes.size();
  size_t replayed = 0;
  if (!fresh) {
    if (!journal_->damage().empty())
      report_.damage = "journal " + options_.snapshot_path + ".journal: " + journal_->damage() + " (tail dropped)";
    for (const auto& rec : journal_->recovered()) {
      persist::ByteReader peek(rec.bytes);
      uint64_t seq = 0;
      try {
        seq = peek.get<uint64_t>();
      } catch (const persist::CorruptBytes&) {
        report_.damage = "journal: record without a sequence number (dropped with the rest)";
        break;
      }
      if (seq <= st.last_record) continue;  // already in the snapshot
      try {
        apply(rec, &st);
        ++replayed;
      } catch (const persist::CorruptBytes& e) {
        // A record the state cannot take (the CRC held: a bug or a foreign file) is not
        // applied; neither is anything after it, which depends on it.
        report_.damage = std::string("journal record ") + std::to_string(seq) + " refused: " + e.what() +
                         " (dropped with the rest)";
        break;
      }
    }
  }
  report_.records_replayed = replayed;
  seq_ = st.last_record;
  recovered_ = std::move(st);
  report_.scans = recovered_.mapper.nodes.size();
  report_.edges = recovered_.mapper.edges.size();
  edges_recorded_ = recovered_.mapper.edges.size();
  // Compact: the recovered state becomes the snapshot, the journal starts empty. Also on a
  // fresh start, so that stale records can never be replayed onto the new map.
  if (fresh || replayed > 0 || !report_.damage.empty() || journal_->records() > 0) {
    save_snapshot(recovered_, options_.snapshot_path);
    journal_->reset();
  }
}

void MapperStore::write_new_edges(persist::ByteWriter& w, const ScanMapper& mapper)
{
  const auto& edges = mapper.graph().edges();
  if (edges.size() < edges_recorded_)
    throw std::logic_error("pose graph lost edges that were journaled");
  w.put(static_cast<uint64_t>(edges.size() - edges_recorded_));
  for (size_t i = edges_recorded_; i < edges.size(); ++i) write_edge(w, edges[i]);
}

void MapperStore::append(uint32_t tag, const std::string& bytes, const ScanMapper& mapper, const ScanIdState& ids)
{
  journal_->append(tag, bytes);
  ++seq_;
  edges_recorded_ = mapper.graph().edges().size();
  if (journal_->records() >= options_.snapshot_every_records) snapshot(mapper, ids);
}

void MapperStore::record_scan(const ScanMapper& mapper, int index, const ScanIdState& ids)
{
  const ScanNode& node = mapper.nodes().at(static_cast<size_t>(index));
  check_finite(node);
  persist::ByteWriter w;
  w.put(seq_ + 1);
  write_ids(w, ids);
  w.put(static_cast<uint64_t>(index));
  write_node(w, node);
  write_new_edges(w, mapper);
  append(kScan, w.take(), mapper, ids);
}

void MapperStore::record_estimates(const ScanMapper& mapper, const ScanIdState& ids)
{
  persist::ByteWriter w;
  w.put(seq_ + 1);
  write_ids(w, ids);
  w.put(static_cast<uint64_t>(mapper.nodes().size()));
  for (const auto& n : mapper.nodes()) {
    check_finite(n);
    write_estimate(w, n);
  }
  write_new_edges(w, mapper);
  append(kEstimates, w.take(), mapper, ids);
}

void MapperStore::snapshot(const ScanMapper& mapper, const ScanIdState& ids)
{
  save_snapshot({mapper.state(), ids, seq_}, options_.snapshot_path);
  journal_->reset();
  edges_recorded_ = mapper.graph().edges().size();
}

}  // namespace rgnav::scan_mapper
