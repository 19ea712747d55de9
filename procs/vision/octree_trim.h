// Deletes the parts of an OctoMap farther than a horizontal radius from a point: the map is
// kept around the robot. OcTree::deleteNode cannot do it in OctoMap 1.9: it leaves inner nodes
// whose child array is allocated but empty, and deleting such a node later trips OctoMap's own
// assertion (Debian's library is built with assertions: the process aborts). This walks the
// tree once from the root with OctoMap's public node API instead, collapsing every subtree
// that is wholly outside into a leaf (which frees its child arrays) before unlinking it.
#pragma once

#include <octomap/OcTree.h>

#include <Eigen/Core>

#include <cstddef>

namespace rgnav::vision {

// Removes every node whose box lies wholly farther than `radius` (in x-y) from `center`
// (tree coordinates); boxes crossing the circle are kept. Returns the number of subtrees removed.
size_t trim_tree(octomap::OcTree& tree, const Eigen::Vector2d& center, double radius);

}  // namespace rgnav::vision
