#include "segmentation_diagnosis.h"

#include <cmath>
#include <sstream>

namespace rgnav::rgmap_pipeline {

namespace {

int32_t room_at(const LabelGrid& g, const Eigen::Vector2d& p)
{
  const int cx = static_cast<int>(std::floor((p.x() - g.origin.x()) / g.resolution));
  const int cy = static_cast<int>(std::floor((p.y() - g.origin.y()) / g.resolution));
  const int reach = static_cast<int>(std::ceil(0.3 / g.resolution));
  int32_t best = 0;
  int best_d2 = reach * reach + 1;
  for (int dy = -reach; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx) {
      const int x = cx + dx, y = cy + dy, d2 = dx * dx + dy * dy;
      if (x < 0 || y < 0 || x >= g.width || y >= g.height || d2 >= best_d2) continue;
      if (const int32_t l = g.at(x, y); l > 0) best = l, best_d2 = d2;
    }
  return best;
}

}  // namespace

SegmentationDiagnosis diagnose_segmentation(const LabelGrid& truth, const RegionCells& found,
                                            const std::map<int64_t, std::vector<Eigen::Vector2d>>& positions)
{
  SegmentationDiagnosis d;
  for (const auto& [rid, cells] : found) {
    RegionDiagnosis r;
    r.region = rid;
    for (int64_t c : cells) {
      if (c < 0 || c >= static_cast<int64_t>(truth.labels.size())) continue;
      if (const int32_t l = truth.labels[static_cast<size_t>(c)]; l > 0) ++r.room_cells[l], ++r.cells;
    }
    if (r.cells == 0) continue;
    for (const auto& [room, n] : r.room_cells)
      if (n > r.best_cells) r.best_room = room, r.best_cells = n;   // ties: the lower label, as the metric
    if (auto p = positions.find(rid); p != positions.end())
      for (const auto& x : p->second) {
        const int32_t room = room_at(truth, x);
        ++r.room_positions[room];
        if (r.path.empty() || r.path.back().first != room) r.path.push_back({room, 0});
        ++r.path.back().second;
      }
    for (const auto& [room, n] : r.room_cells) {
      if (room == r.best_room) continue;
      (r.room_positions.count(room) ? r.driven_cells : r.seen_cells) += n;
    }
    d.seen_loss += static_cast<double>(r.seen_cells) / static_cast<double>(r.cells);
    d.driven_loss += static_cast<double>(r.driven_cells) / static_cast<double>(r.cells);
    d.regions.push_back(std::move(r));
  }
  if (!d.regions.empty()) {
    d.seen_loss /= static_cast<double>(d.regions.size());
    d.driven_loss /= static_cast<double>(d.regions.size());
  }
  return d;
}

std::string to_text(const SegmentationDiagnosis& d, const std::vector<std::string>& room_names)
{
  auto name = [&](int32_t l) {
    return l > 0 && static_cast<size_t>(l) <= room_names.size() ? room_names[static_cast<size_t>(l) - 1] : std::string("-");
  };
  std::ostringstream o;
  o.precision(2);
  o << std::fixed;
  for (const auto& r : d.regions) {
    o << "R" << r.region << " cells " << r.cells << " best " << name(r.best_room) << " "
      << static_cast<double>(r.best_cells) / static_cast<double>(r.cells) << " seen "
      << static_cast<double>(r.seen_cells) / static_cast<double>(r.cells) << " driven "
      << static_cast<double>(r.driven_cells) / static_cast<double>(r.cells) << " |";
    for (const auto& [room, n] : r.room_cells) {
      if (room == r.best_room) continue;
      if (static_cast<double>(n) < 0.02 * static_cast<double>(r.cells)) continue;
      o << " " << name(room) << (r.room_positions.count(room) ? "*" : "") << ":" << n;
    }
    o << " | positions";
    for (const auto& [room, n] : r.room_positions) o << " " << name(room) << ":" << n;
    o << " | path";
    for (const auto& [room, n] : r.path) o << " " << name(room) << "x" << n;
    o << "\n";
  }
  o << "loss seen-through " << d.seen_loss << " driven-through " << d.driven_loss << "\n";
  return o.str();
}

}  // namespace rgnav::rgmap_pipeline
