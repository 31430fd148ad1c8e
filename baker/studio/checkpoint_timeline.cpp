#include "studio/checkpoint_timeline.h"

#include <algorithm>
#include <stdexcept>

namespace rockbake {
namespace {

std::size_t rowSpanBytes(const RowSpans& spans) {
  std::size_t bytes = spans.first.capacity() * sizeof(std::int32_t) + spans.values.capacity() * sizeof(spans.values[0]);
  for (const auto& row : spans.values) bytes += row.capacity() * sizeof(float);
  return bytes;
}

}  // namespace

std::size_t snapshotBytes(const SimulationSnapshot& snapshot) {
  const VoxelRock& rock = snapshot.rock;
  return sizeof(SimulationSnapshot) + rock.material.capacity() + rock.rind.capacity() + rowSpanBytes(rock.integrity) +
         rowSpanBytes(rock.durability) + snapshot.colluvium_columns.capacity() * sizeof(std::int64_t);
}

void CheckpointTimeline::restart(SimulationSnapshot start, int spacing) {
  kept_.clear();
  bytes_ = 0;
  spacing_ = std::max(1, spacing);
  keep(std::move(start));
}

bool CheckpointTimeline::wants(int cycle) const {
  return cycle % spacing_ == 0 && !kept_.contains(cycle);
}

void CheckpointTimeline::keep(SimulationSnapshot snapshot) {
  const int cycle = snapshot.cycle;
  const std::size_t bytes = snapshotBytes(snapshot);
  if (const auto it = kept_.find(cycle); it != kept_.end()) {
    bytes_ -= it->second.bytes;
    kept_.erase(it);
  }
  kept_.emplace(cycle, Kept{std::move(snapshot), bytes});
  bytes_ += bytes;
  while (kept_.size() > 1 && (kept_.size() > bounds_.max_count || bytes_ > bounds_.max_bytes)) thin();
}

void CheckpointTimeline::thin() {
  spacing_ *= 2;
  for (auto it = kept_.begin(); it != kept_.end();) {
    if (it->first != 0 && it->first % spacing_ != 0) {
      bytes_ -= it->second.bytes;
      it = kept_.erase(it);
    } else {
      ++it;
    }
  }
}

const SimulationSnapshot& CheckpointTimeline::atOrBefore(int cycle) const {
  auto it = kept_.upper_bound(cycle);
  if (it == kept_.begin()) throw std::logic_error("CheckpointTimeline: no checkpoint at or before a cycle");
  return std::prev(it)->second.snapshot;
}

void CheckpointTimeline::dropAfter(int cycle) {
  for (auto it = kept_.upper_bound(cycle); it != kept_.end();) {
    bytes_ -= it->second.bytes;
    it = kept_.erase(it);
  }
}

std::vector<int> CheckpointTimeline::cycles() const {
  std::vector<int> cycles;
  for (const auto& [cycle, kept] : kept_) cycles.push_back(cycle);
  return cycles;
}

}  // namespace rockbake
