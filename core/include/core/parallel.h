#pragma once
// TBB names the project uses, and the helper that runs work in an arena sized from the
// context. Modules never start raw threads, and results never depend on the thread count: no
// floating-point atomics, each output has one owner or partial sums combine in a fixed order.

#include <cstddef>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/context.h"

namespace penumbra {

using tbb::blocked_range;
using tbb::parallel_for;

/// Number of worker threads the context asks for (0 = hardware concurrency).
int thread_count(const Context& ctx);

/// Runs \p fn inside a task arena limited to the context's thread count.
template <typename Fn> decltype(auto) run_in_arena(const Context& ctx, Fn&& fn) {
    tbb::task_arena arena(thread_count(ctx));
    return arena.execute(std::forward<Fn>(fn));
}

/// Parallel loop over [0, n) with a fixed grain size. Each index must own its outputs.
template <typename Fn> void parallel_for_index(std::size_t n, std::size_t grain, Fn&& fn) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain ? grain : 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i)
                              fn(i);
                      });
}

} // namespace penumbra
