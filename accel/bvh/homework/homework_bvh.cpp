#include "accel/bvh/homework/homework_bvh.h"

#include <algorithm>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "core/error.h"

namespace prism {
namespace {

float node_area(const HomeworkBvhNode& n) { return Bounds3{n.lower, n.upper}.area(); }

bool contains(const HomeworkBvhNode& n, const Bounds3& b) {
  return glm::all(glm::lessThanEqual(n.lower, b.lower)) &&
         glm::all(glm::lessThanEqual(b.upper, n.upper));
}

[[noreturn]] void broken(const std::string& what, size_t node) {
  throw Error(ErrorKind::kInternal,
              "bvh invariant broken at node " + std::to_string(node) + ": " + what);
}

}  // namespace

AccelStats homework_bvh_stats(const HomeworkBvh& bvh) {
  AccelStats s;
  if (bvh.nodes.empty()) return s;
  s.nodes = bvh.nodes.size();
  s.max_depth = bvh.max_depth;
  s.bytes = bvh.nodes.size() * sizeof(HomeworkBvhNode) + bvh.prims.size() * sizeof(PrimitiveId);
  const double root_area = node_area(bvh.nodes[0]);
  for (const HomeworkBvhNode& n : bvh.nodes) {
    // A flat or point-like root makes every ratio 0/0: count each node once instead.
    const double ratio = root_area > 0.0 ? node_area(n) / root_area : 1.0;
    if (n.is_leaf()) {
      ++s.leaves;
      s.sah_cost += ratio * double(n.count);
    } else {
      s.sah_cost += ratio;
    }
  }
  return s;
}

void check_homework_bvh(const HomeworkBvh& bvh, const std::vector<HomeworkBuildPrimitive>& prims) {
  if (bvh.nodes.empty() != prims.empty()) broken("empty tree for primitives or vice versa", 0);
  if (bvh.prims.size() != prims.size()) broken("primitive count differs from the input", 0);
  if (bvh.nodes.empty()) return;
  const auto key = [](PrimitiveId r) { return uint64_t(r.geom_id) << 32 | r.prim_id; };
  std::unordered_map<uint64_t, const HomeworkBuildPrimitive*> input;
  for (const auto& p : prims) input.emplace(key(p.id), &p);
  std::unordered_set<uint64_t> seen;

  // Children follow their parent in the array, so one forward pass sees every parent first.
  std::vector<size_t> depth(bvh.nodes.size(), 0);
  std::vector<int> references(bvh.nodes.size(), 0);
  references[0] = 1;
  size_t max_depth = 0;
  for (size_t i = 0; i < bvh.nodes.size(); ++i) {
    const HomeworkBvhNode& n = bvh.nodes[i];
    if (references[i] != 1)
      broken("node is reached " + std::to_string(references[i]) + " times", i);
    max_depth = std::max(max_depth, depth[i]);
    if (n.is_leaf()) {
      if (size_t(n.index) + n.count > bvh.prims.size()) broken("leaf range out of bounds", i);
      for (uint32_t k = n.index; k < n.index + n.count; ++k) {
        const auto it = input.find(key(bvh.prims[k]));
        if (it == input.end()) broken("unknown primitive", i);
        if (!seen.insert(it->first).second) broken("primitive repeated", i);
        if (!contains(n, it->second->bounds)) broken("leaf box misses a primitive", i);
      }
      continue;
    }
    const size_t left = i + 1, right = n.index;
    if (right <= left || right >= bvh.nodes.size()) broken("child index out of range", i);
    for (const size_t c : {left, right}) {
      ++references[c];
      depth[c] = depth[i] + 1;
      const HomeworkBvhNode& child = bvh.nodes[c];
      if (!contains(n, Bounds3{child.lower, child.upper})) broken("child box outside parent", i);
    }
  }
  if (seen.size() != prims.size()) broken("some primitives are in no leaf", 0);
  if (max_depth != bvh.max_depth) broken("max_depth is wrong", 0);
}

}  // namespace prism
