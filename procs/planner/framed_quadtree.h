// A framed quadtree over a region grid (diss. 5.4, Fig. 5.6e; Chen, Szczerba & Uhran 1997):
// the grid is split into square quads until each is one cost level (or blocked); every free
// quad carries a frame of its border cells, and A* runs over those border cells: inside a quad
// any border cell reaches any other on a straight line (the quad is uniform), and a border cell
// steps to the 8 neighbouring cells of adjoining quads. Large open quads so cost few nodes yet
// are crossed in any direction, not through their centres (Fig. 5.7).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <vector>

#include "planner/region_grid.h"

namespace rgnav::planner {

struct QuadSearchStats
{
  int expanded = 0;        // border cells taken off the open list
  int quads = 0;           // free quads in the tree
};

class FramedQuadtree
{
 public:
  struct Quad
  {
    int x0 = 0, y0 = 0, size = 1;   // cells
    uint8_t level = 0;              // cost level of all its cells
  };

  // max_quad_cells bounds a quad's edge (a large quad has many border cells to connect).
  explicit FramedQuadtree(const RegionGrid& grid, int max_quad_cells = 32);

  const std::vector<Quad>& quads() const { return quads_; }
  // Index of the free quad holding cell c; -1 when c is blocked or outside.
  int quad_at(const Cell& c) const;

  // Cheapest path from the centre of `start` to the centre of `goal` (both free), as the cells
  // where it turns: start, border cells, goal. nullopt when the goal cannot be reached. Not
  // for concurrent calls on one tree (it reuses its scratch arrays).
  std::optional<std::vector<Cell>> search(const Cell& start, const Cell& goal, QuadSearchStats* stats = nullptr) const;

 private:
  void build(int x0, int y0, int size);
  // Border cells of quad q, each once.
  void border_cells(int q, std::vector<Cell>* out) const;

  // Per-search state over the grid, reused (searches of one tree run one at a time).
  struct Scratch
  {
    std::vector<uint32_t> stamp;
    std::vector<float> g;
    std::vector<int> parent;
    std::vector<uint8_t> closed;
    uint32_t search = 0;
  };

  const RegionGrid& grid_;
  const int max_quad_;
  mutable Scratch scratch_;
  std::vector<Quad> quads_;
  std::vector<int> quad_of_cell_;   // row-major, -1 for blocked
};

}  // namespace rgnav::planner
