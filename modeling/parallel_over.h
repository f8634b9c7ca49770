#pragma once
// A parallel loop over indices 0..n-1 for the modeling layer's coarse tasks (zones, chunks of
// candidate face pairs). TBB's parallel_for in a task arena of `threads` workers (0: the
// caller's arena, all cores unless a tbb::global_control says otherwise), except in
// ThreadSanitizer builds: Debian's libtbb is not instrumented, so its internal hand-offs are
// invisible to TSan and every task looks racy. There the same loop runs on std::threads taking
// indices from an atomic counter (join is a synchronisation TSan sees), so the reports that
// remain are about the task bodies and the state they share.
//
// body(i) may run concurrently for different i and in any order; callers that need a
// deterministic result write into per-index slots and combine them in index order.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace ps {

template <class Body>
void parallel_over(std::size_t n, int threads, const Body& body) {
#if defined(__SANITIZE_THREAD__)
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t k = std::min<std::size_t>(n, threads > 0 ? static_cast<std::size_t>(threads) : hw);
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> pool;
  for (std::size_t t = 0; t < k; ++t)
    pool.emplace_back([&] {
      for (std::size_t i = next++; i < n; i = next++) body(i);
    });
  for (auto& th : pool) th.join();
#else
  auto loop = [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
    });
  };
  if (threads > 0) {
    tbb::task_arena arena(threads);
    arena.execute(loop);
  } else {
    loop();  // the caller's arena, or TBB's default (bounded by any tbb::global_control)
  }
#endif
}

// body(begin, end) over consecutive ranges covering 0..n-1, in parallel when n is at least
// `min_parallel` (below that, one call on the calling thread: the hand-over costs more). For
// per-element loops whose iterations write only their own slots, so the result does not depend
// on the split.
template <class Body>
void parallel_ranges(std::size_t n, std::size_t min_parallel, const Body& body) {
  if (n < min_parallel || n < 2) {
    if (n > 0) body(std::size_t{0}, n);
    return;
  }
  constexpr std::size_t kChunks = 32;
  const std::size_t step = (n + kChunks - 1) / kChunks;
  parallel_over(kChunks, 0, [&](std::size_t c) {
    const std::size_t begin = std::min(n, c * step), end = std::min(n, (c + 1) * step);
    if (begin < end) body(begin, end);
  });
}

}  // namespace ps
