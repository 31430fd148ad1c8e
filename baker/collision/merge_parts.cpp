#include "collision/merge_parts.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <map>
#include <queue>
#include <tuple>
#include <utility>

#include <tbb/parallel_for.h>

#include "collision/reduce_hull.h"
#include "geometry/disjoint_set.h"

namespace rockbake {
namespace {

using Pair = std::array<std::uint32_t, 2>;  // node numbers, lower first

struct Node {
  PointHull hull;
  std::size_t voxels = 0;
  double air = 0.0;          // air voxels inside the hull
  double capped_air = -1.0;  // inside the hull with its vertices capped; -1 until needed
  Vec3d lo{}, hi{};          // the hull's bounding box
  // Alive neighbours, sorted by number, each with the cost of merging with it
  // as last queued: measured, or estimated for a pair not measured yet.
  std::vector<std::pair<std::uint32_t, double>> neighbours;
  bool alive = true;
};

struct Candidate {
  double cost;
  Pair pair;
  bool measured;  // false: an estimate, measured when it comes first
  // The priority queue pops its greatest: the cheapest merge, ties to the lower numbers.
  bool operator<(const Candidate& o) const {
    return std::tie(o.cost, o.pair, o.measured) < std::tie(cost, pair, measured);
  }
};

std::array<Vec3d, 2> boundingBox(const std::vector<Vec3d>& points) {
  std::array<Vec3d, 2> box{points.front(), points.front()};
  for (const Vec3d& v : points)
    for (int a = 0; a < 3; ++a) box[0][a] = std::min(box[0][a], v[a]), box[1][a] = std::max(box[1][a], v[a]);
  return box;
}

double airInside(const PointHull& hull, const AirCounter& air) {
  const auto [lo, hi] = boundingBox(hull.vertices);
  return double(air.count(hull.planes, lo, hi));
}

Node makeNode(PointHull hull, std::size_t voxels, double air) {
  Node n;
  n.hull = std::move(hull);
  n.voxels = voxels;
  n.air = air;
  const auto box = boundingBox(n.hull.vertices);
  n.lo = box[0], n.hi = box[1];
  return n;
}

// The hull of two nodes' hulls together (their vertices in one sorted list,
// so that it does not depend on which is which).
PointHull jointHull(const Node& a, const Node& b) {
  std::vector<Vec3d> points;
  points.reserve(a.hull.vertices.size() + b.hull.vertices.size());
  std::merge(a.hull.vertices.begin(), a.hull.vertices.end(), b.hull.vertices.begin(), b.hull.vertices.end(),
             std::back_inserter(points));
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return hullOfPoints(points);
}

// Gap between two nodes' bounding boxes (0 where they overlap), squared.
double boxGap2(const Node& a, const Node& b) {
  double g2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double g = std::max({0.0, b.lo[k] - a.hi[k], a.lo[k] - b.hi[k]});
    g2 += g * g;
  }
  return g2;
}

void setCost(Node& node, std::uint32_t neighbour, double cost) {
  auto it = std::lower_bound(node.neighbours.begin(), node.neighbours.end(), std::pair{neighbour, -1e300});
  if (it != node.neighbours.end() && it->first == neighbour)
    it->second = cost;
  else
    node.neighbours.insert(it, {neighbour, cost});
}

class Merger {
 public:
  Merger(const VoxelParts& parts, const AirCounter& air, const MergeParams& params) : air_(air), params_(params) {
    nodes_.resize(parts.parts.size());
    for (std::size_t i = 0; i < nodes_.size(); ++i)
      nodes_[i] = makeNode(parts.parts[i].hull, parts.parts[i].voxels, double(parts.parts[i].air));
    alive_ = nodes_.size();
    std::size_t voxels = 0;
    for (const VoxelPart& p : parts.parts) voxels += p.voxels;
    budget_ = params.free_fraction * double(voxels);
    std::vector<Pair> pairs = parts.adjacent;
    const std::vector<Pair> links = linkComponents(parts.adjacent);
    pairs.insert(pairs.end(), links.begin(), links.end());
    measure(pairs);
  }

  std::vector<MergedPiece> run() {
    while (true) {
      if (queue_.empty()) {
        if (alive_ <= params_.max_pieces || !joinNearest()) break;
        continue;
      }
      const Candidate c = queue_.top();
      if (!valid(c)) {
        queue_.pop();
      } else if (!c.measured) {
        measureEstimates();
      } else {
        if (alive_ <= params_.max_pieces && c.cost > budget_) break;
        queue_.pop();
        if (alive_ > params_.max_pieces) {
          merge(c.pair);
        } else if (const double capped = cappedCost(c.pair); capped <= budget_) {
          budget_ -= capped;
          merge(c.pair);
        }
      }
    }
    std::vector<MergedPiece> pieces;
    for (Node& n : nodes_)
      if (n.alive) pieces.push_back({std::move(n.hull), n.voxels});
    return pieces;
  }

 private:
  bool valid(const Candidate& c) const { return nodes_[c.pair[0]].alive && nodes_[c.pair[1]].alive; }

  // Measures the pairs' costs, in parallel, records them and queues them in
  // order; keeps each joint hull for the merge it may lead to.
  void measure(const std::vector<Pair>& pairs) {
    std::vector<Joint> joints(pairs.size());
    tbb::parallel_for(std::size_t(0), pairs.size(), [&](std::size_t i) {
      joints[i].hull = jointHull(nodes_[pairs[i][0]], nodes_[pairs[i][1]]);
      joints[i].air = airInside(joints[i].hull, air_);
    });
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const auto [a, b] = pairs[i];
      const double cost = joints[i].air - nodes_[a].air - nodes_[b].air;
      setCost(nodes_[a], b, cost);
      setCost(nodes_[b], a, cost);
      queue_.push({cost, pairs[i], true});
      joints_[pairs[i]] = std::move(joints[i]);
    }
  }

  // Measures the estimates at the front of the queue, a batch at a time (the
  // same as one at a time: nothing merges in between, and a cost depends only
  // on its two nodes).
  void measureEstimates() {
    constexpr std::size_t kBatch = 16;
    std::vector<Pair> pairs;
    while (!queue_.empty() && pairs.size() < kBatch && !queue_.top().measured) {
      if (valid(queue_.top())) pairs.push_back(queue_.top().pair);
      queue_.pop();
    }
    measure(pairs);
  }

  // The air the pair's merge adds once each hull's vertices are capped.
  double cappedCost(const Pair& pair) {
    const auto capped = [&](const PointHull& hull) {
      const CappedHull c = reduceHull(hull, params_.max_vertices);
      const auto [lo, hi] = boundingBox(c.vertices);
      return double(air_.count(c.planes, lo, hi));
    };
    Joint& joint = joints_.at(pair);
    if (joint.capped_air < 0) joint.capped_air = capped(joint.hull);
    double cost = joint.capped_air;
    for (const std::uint32_t part : pair) {
      Node& n = nodes_[part];
      if (n.capped_air < 0) n.capped_air = capped(n.hull);
      cost -= n.capped_air;
    }
    return cost;
  }

  // Merges a pair into a new node. Its costs with its neighbours are
  // estimated, not measured (most would never be used): the least of what
  // merging the neighbour with either part was last found to cost.
  void merge(const Pair& pair) {
    const auto [a, b] = pair;
    const auto c = std::uint32_t(nodes_.size());
    const auto joint = joints_.find(pair);
    Node merged = makeNode(std::move(joint->second.hull), nodes_[a].voxels + nodes_[b].voxels, joint->second.air);
    merged.capped_air = joint->second.capped_air;
    for (const std::uint32_t part : {a, b})  // the joint hulls kept for the parts' other pairs go
      for (const auto& [n, cost] : nodes_[part].neighbours) joints_.erase({std::min(part, n), std::max(part, n)});
    for (const std::uint32_t part : {a, b})
      for (const auto& [n, cost] : nodes_[part].neighbours) {
        if (n == a || n == b) continue;
        auto it = std::lower_bound(merged.neighbours.begin(), merged.neighbours.end(), std::pair{n, -1e300});
        if (it != merged.neighbours.end() && it->first == n)
          it->second = std::min(it->second, cost);
        else
          merged.neighbours.insert(it, {n, cost});
      }
    for (const std::uint32_t part : {a, b}) nodes_[part] = Node{}, nodes_[part].alive = false;
    nodes_.push_back(std::move(merged));
    --alive_;
    for (const auto& [n, cost] : nodes_[c].neighbours) {
      auto& list = nodes_[n].neighbours;
      std::erase_if(list, [&](const auto& e) { return e.first == a || e.first == b; });
      list.push_back({c, cost});  // the newest node has the highest number: the list stays sorted
      queue_.push({cost, {n, c}, false});
    }
  }

  // Pairs that join each set of touching parts (a fallen block, a loose voxel)
  // to the nearest parts of the others, by bounding-box gap: its kLinks
  // nearest pairs. Without them a loose voxel would keep a piece of its own
  // to the end, and the rest would have to merge around it.
  std::vector<Pair> linkComponents(const std::vector<Pair>& adjacent) const {
    constexpr std::size_t kLinks = 4;
    // Components of the touching graph, numbered by their smallest parts.
    DisjointSet touching(nodes_.size());
    for (const auto& [a, b] : adjacent) touching.unite(a, b);
    const std::vector<std::uint32_t> component = touching.labels();
    if (std::all_of(component.begin(), component.end(), [](std::uint32_t r) { return r == 0; })) return {};
    // Each part's nearest part in another component.
    std::vector<std::pair<double, std::uint32_t>> nearest(nodes_.size(), {1e300, 0});
    tbb::parallel_for(std::size_t(0), nodes_.size(), [&](std::size_t i) {
      for (std::uint32_t j = 0; j < nodes_.size(); ++j)
        if (component[j] != component[i]) nearest[i] = std::min(nearest[i], {boxGap2(nodes_[i], nodes_[j]), j});
    });
    // Each component's kLinks best.
    std::vector<std::vector<std::pair<double, Pair>>> best(nodes_.size());
    for (std::uint32_t i = 0; i < nodes_.size(); ++i) {
      const std::uint32_t j = nearest[i].second;
      best[component[i]].push_back({nearest[i].first, {std::min(i, j), std::max(i, j)}});
    }
    std::vector<Pair> links;
    for (auto& list : best) {
      const std::size_t k = std::min(kLinks, list.size());
      std::partial_sort(list.begin(), list.begin() + std::ptrdiff_t(k), list.end());
      for (std::size_t n = 0; n < k; ++n) links.push_back(list[n].second);
    }
    std::sort(links.begin(), links.end());
    links.erase(std::unique(links.begin(), links.end()), links.end());
    return links;
  }

  // Joins every piece to its nearest few others by bounding-box gap, among
  // those it does not touch; false when there is nothing to join.
  bool joinNearest() {
    constexpr std::size_t kNearest = 4;
    std::vector<std::uint32_t> alive;
    for (std::uint32_t i = 0; i < nodes_.size(); ++i)
      if (nodes_[i].alive) alive.push_back(i);
    std::vector<std::vector<std::uint32_t>> nearest(alive.size());
    tbb::parallel_for(std::size_t(0), alive.size(), [&](std::size_t i) {
      std::vector<std::pair<double, std::uint32_t>> others;
      for (const std::uint32_t j : alive)
        if (j != alive[i]) others.push_back({boxGap2(nodes_[alive[i]], nodes_[j]), j});
      const std::size_t k = std::min(kNearest, others.size());
      std::partial_sort(others.begin(), others.begin() + std::ptrdiff_t(k), others.end());
      for (std::size_t n = 0; n < k; ++n) nearest[i].push_back(others[n].second);
    });
    std::vector<Pair> pairs;
    for (std::size_t i = 0; i < alive.size(); ++i)
      for (const std::uint32_t j : nearest[i]) pairs.push_back({std::min(alive[i], j), std::max(alive[i], j)});
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    measure(pairs);
    return !pairs.empty();
  }

  struct Joint {
    PointHull hull;
    double air = 0.0;
    double capped_air = -1.0;
  };
  const AirCounter& air_;
  MergeParams params_;
  std::map<Pair, Joint> joints_;  // measured pairs' joint hulls, until a merge uses or outdates them
  std::vector<Node> nodes_;
  std::size_t alive_ = 0;
  double budget_ = 0.0;  // air the merges below max_pieces may still add
  std::priority_queue<Candidate> queue_;
};

}  // namespace

std::vector<MergedPiece> mergeParts(const VoxelParts& parts, const AirCounter& air, const MergeParams& params) {
  if (parts.parts.empty()) return {};
  return Merger(parts, air, params).run();
}

}  // namespace rockbake
