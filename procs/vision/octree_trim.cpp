#include "vision/octree_trim.h"

#include <algorithm>
#include <cmath>

namespace rgnav::vision {

namespace {

struct Trim
{
  octomap::OcTree& tree;
  Eigen::Vector2d center;
  double radius;
  size_t removed = 0;

  // Nearest and farthest distance of a square column (centre c, half edge h) from the centre.
  double nearest(const Eigen::Vector2d& c, double h) const
  {
    const Eigen::Vector2d d = ((c - center).cwiseAbs().array() - h).max(0.0).matrix();
    return d.norm();
  }
  double farthest(const Eigen::Vector2d& c, double h) const { return ((c - center).cwiseAbs().array() + h).matrix().norm(); }

  // Makes `node` a leaf without children array. `emptied`: its children were all unlinked by
  // this walk (the array is still allocated though OctoMap reports no children).
  void make_leaf(octomap::OcTreeNode* node, bool emptied)
  {
    if (!emptied && !tree.nodeHasChildren(node)) return;
    for (unsigned i = 0; i < 8; ++i) {
      if (!tree.nodeChildExists(node, i)) tree.createNodeChild(node, i);
      octomap::OcTreeNode* child = tree.getNodeChild(node, i);
      make_leaf(child, false);
      child->setLogOdds(0.f);   // equal values make the node collapsible
    }
    tree.pruneNode(node);
  }

  enum class Verdict { kKeep, kOutside, kEmptied };

  // What the parent does with `node`: keep it, or unlink it (wholly outside; or all its
  // children were unlinked here, which leaves its child array allocated but empty).
  Verdict walk(octomap::OcTreeNode* node, const Eigen::Vector2d& c, double half)
  {
    if (nearest(c, half) > radius) return Verdict::kOutside;
    if (farthest(c, half) <= radius || !tree.nodeHasChildren(node)) return Verdict::kKeep;
    const double q = half / 2;
    bool any_left = false;
    for (unsigned i = 0; i < 8; ++i) {
      if (!tree.nodeChildExists(node, i)) continue;
      // OctoMap's child index: bit 0 = +x half, bit 1 = +y half, bit 2 = +z half.
      const Eigen::Vector2d cc(c.x() + ((i & 1) ? q : -q), c.y() + ((i & 2) ? q : -q));
      octomap::OcTreeNode* child = tree.getNodeChild(node, i);
      const Verdict v = walk(child, cc, q);
      if (v == Verdict::kKeep) {
        any_left = true;
        continue;
      }
      make_leaf(child, v == Verdict::kEmptied);
      tree.deleteNodeChild(node, i);
      ++removed;
    }
    if (!any_left) return Verdict::kEmptied;
    node->updateOccupancyChildren();
    return Verdict::kKeep;
  }
};

}  // namespace

size_t trim_tree(octomap::OcTree& tree, const Eigen::Vector2d& center, double radius)
{
  octomap::OcTreeNode* root = tree.getRoot();
  if (root == nullptr) return 0;
  Trim t{tree, center, radius};
  // The root's cube is centred on the origin, 2^depth voxels on an edge.
  const double half = 0.5 * tree.getResolution() * static_cast<double>(1u << tree.getTreeDepth());
  if (t.walk(root, Eigen::Vector2d::Zero(), half) != Trim::Verdict::kKeep) {
    tree.clear();   // nothing within the radius
    return 1;
  }
  return t.removed;
}

}  // namespace rgnav::vision
