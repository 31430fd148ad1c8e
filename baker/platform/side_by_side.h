// Independent jobs run side by side on TBB's workers; returns when all have
// finished.
//
// Why not tbb::parallel_invoke alone: there, an exception in one job (a
// std::bad_alloc, say) cancels the other's nested parallel loops, which then
// return early and silently, and the other job goes on with half-computed
// results. Here each job runs to its own end, its exception caught; then the
// first job's exception, else the second's, is rethrown, so the error a caller
// sees does not depend on timing.
#pragma once

#include <cstddef>
#include <functional>

namespace rockbake {

void sideBySide(const std::function<void()>& first, const std::function<void()>& second);

// job(0) … job(count - 1) side by side, each run to its end; the exception of
// the lowest-numbered job that threw, if any, is rethrown.
void allSideBySide(std::size_t count, const std::function<void(std::size_t)>& job);

}  // namespace rockbake
