#include "accel/bvh/reinsertion_optimizer.h"

#include <algorithm>
#include <queue>

namespace prism {
namespace {

constexpr int kNone = -1;
/// Each pass tries the kCandidates largest nodes. Measured on the CS184 meshes (2026-12-04),
/// trying the largest eighth of the nodes bought no more than these; on meshes of 100k
/// triangles and more the search, which is serial, would cost more than the build itself.
constexpr size_t kCandidates = 1024;

Bounds3 united(Bounds3 a, const Bounds3& b) {
  a.extend(b);
  return a;
}

/// The tree with explicit links, so that subtrees can move.
class LinkedTree {
 public:
  explicit LinkedTree(const BinaryBvh& bvh) {
    const size_t n = bvh.node_count;
    box_.resize(n);
    left_.assign(n, kNone);
    right_.assign(n, kNone);
    parent_.assign(n, kNone);
    leaf_first_.assign(n, 0);
    leaf_count_.assign(n, 0);
    for (size_t i = 0; i < n; ++i) {
      const BinaryNode& node = bvh.nodes[i];
      box_[i] = node.bounds();
      if (node.is_leaf()) {
        leaf_first_[i] = node.first;
        leaf_count_[i] = node.count;
      } else {
        left_[i] = static_cast<int>(node.first);
        right_[i] = static_cast<int>(node.first + 1);
        parent_[node.first] = parent_[node.first + 1] = static_cast<int>(i);
      }
    }
  }

  /// One round over the kCandidates largest nodes but the root and its children, largest first.
  size_t pass() {
    std::vector<int> order;
    for (int i = 0; i < static_cast<int>(box_.size()); ++i) {
      if (parent_[i] != kNone && parent_[i] != root_) order.push_back(i);
    }
    std::vector<float> area(box_.size());
    for (size_t i = 0; i < box_.size(); ++i) area[i] = box_[i].area();
    // The largest nodes are where a move saves most.
    const size_t tried = std::min(order.size(), kCandidates);
    const auto larger = [&](int a, int b) {
      return area[a] != area[b] ? area[a] > area[b] : a < b;
    };
    const auto cut = order.begin() + static_cast<std::ptrdiff_t>(tried);
    std::nth_element(order.begin(), cut, order.end(), larger);
    std::sort(order.begin(), cut, larger);
    order.resize(tried);
    size_t moves = 0;
    // Moves made earlier in the pass can turn a candidate into the root or a child of it.
    for (int node : order) {
      if (parent_[node] != kNone && parent_[node] != root_ && reinsert(node)) ++moves;
    }
    return moves;
  }

  /// Levels of the tree, the root's counted.
  int depth() const {
    int deepest = 0;
    std::vector<std::pair<int, int>> stack{{root_, 1}};
    while (!stack.empty()) {
      const auto [n, d] = stack.back();
      stack.pop_back();
      deepest = std::max(deepest, d);
      if (left_[n] != kNone) {
        stack.push_back({left_[n], d + 1});
        stack.push_back({right_[n], d + 1});
      }
    }
    return deepest;
  }

  /// Writes the tree back in BinaryBvh's layout: root 0, children adjacent, in depth-first order.
  void write(BinaryBvh& bvh) const {
    std::vector<int> old_of_new;
    old_of_new.reserve(box_.size());
    old_of_new.push_back(root_);
    for (size_t k = 0; k < old_of_new.size(); ++k) {
      const int old = old_of_new[k];
      BinaryNode& out = bvh.nodes[k];
      out.set_bounds(box_[old]);
      if (left_[old] == kNone) {
        out.first = leaf_first_[old];
        out.count = leaf_count_[old];
      } else {
        out.first = static_cast<uint32_t>(old_of_new.size());
        out.count = 0;
        old_of_new.push_back(left_[old]);
        old_of_new.push_back(right_[old]);
      }
    }
    bvh.node_count = old_of_new.size();
  }

 private:
  int sibling(int node) const {
    const int p = parent_[node];
    return left_[p] == node ? right_[p] : left_[p];
  }

  void replace_child(int parent, int old_child, int new_child) {
    if (parent == kNone) {
      root_ = new_child;
    } else if (left_[parent] == old_child) {
      left_[parent] = new_child;
    } else {
      right_[parent] = new_child;
    }
    parent_[new_child] = parent;
  }

  /// Refits the boxes from `node` up to the root; returns the sum of the areas' changes.
  double refit_from(int node) {
    double change = 0.0;
    for (int n = node; n != kNone; n = parent_[n]) {
      const double before = box_[n].area();
      box_[n] = united(box_[left_[n]], box_[right_[n]]);
      change += box_[n].area() - before;
    }
    return change;
  }

  /// The node whose sibling `box` would best become, and the interior area that would add.
  std::pair<int, double> best_position(const Bounds3& box) const {
    const double box_area = box.area();
    struct Candidate {
      double induced;  ///< area the ancestors of `node` gain
      int node;
      bool operator<(const Candidate& o) const { return induced > o.induced; }
    };
    std::priority_queue<Candidate> queue;
    queue.push({0.0, root_});
    int best = root_;
    double best_cost = kInfinity;
    while (!queue.empty()) {
      const Candidate c = queue.top();
      queue.pop();
      if (c.induced + box_area >= best_cost) break;
      const double merged = united(box_[c.node], box).area();
      const double cost = c.induced + merged;
      if (cost < best_cost) {
        best_cost = cost;
        best = c.node;
      }
      const double induced = c.induced + merged - box_[c.node].area();
      if (left_[c.node] != kNone && induced + box_area < best_cost) {
        queue.push({induced, left_[c.node]});
        queue.push({induced, right_[c.node]});
      }
    }
    return {best, best_cost};
  }

  /// Removes `node` with its parent and inserts both where the interior area grows least.
  bool reinsert(int node) {
    const int p = parent_[node];
    const int s = sibling(node);
    const int g = parent_[p];
    const bool node_was_left = left_[p] == node;
    // Take p out (s takes its place under g): the tree loses p's area and g's ancestors shrink.
    const double removed = box_[p].area() - detach(g, p, s);
    const auto [target, added] = best_position(box_[node]);
    const bool moved = target != s && added < removed * (1.0 - 1e-6);
    // Put back where it was, the children in their order, when no place is better.
    attach(p, node, moved ? target : s, !moved && node_was_left);
    return moved;
  }

  /// Replaces p by s under g and refits; returns the change (<= 0) of the areas from g up.
  double detach(int g, int p, int s) {
    replace_child(g, p, s);
    parent_[p] = kNone;
    return refit_from(g);
  }

  /// Makes p the parent of `node` and of `target`, in target's place, and refits.
  void attach(int p, int node, int target, bool node_left) {
    const int tp = parent_[target];
    replace_child(tp, target, p);
    left_[p] = node_left ? node : target;
    right_[p] = node_left ? target : node;
    parent_[target] = p;
    parent_[node] = p;
    box_[p] = united(box_[target], box_[node]);
    if (tp != kNone) refit_from(tp);
  }

  std::vector<Bounds3> box_;
  std::vector<int> left_, right_, parent_;
  std::vector<uint32_t> leaf_first_, leaf_count_;
  int root_ = 0;
};

}  // namespace

size_t optimize_by_reinsertion(BinaryBvh& bvh, int passes) {
  if (bvh.node_count == 0 || passes <= 0) return 0;
  LinkedTree tree(bvh);
  size_t moves = 0;
  for (int i = 0; i < passes; ++i) {
    const size_t m = tree.pass();
    moves += m;
    if (m == 0) break;
  }
  if (moves == 0 || tree.depth() > kMaxBvhDepth) return 0;
  tree.write(bvh);
  return moves;
}

}  // namespace prism
