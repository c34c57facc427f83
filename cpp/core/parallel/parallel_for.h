// Deterministic parallel loops over an index range, on the process-wide pool (thread_pool.h).
//
// The range [begin, end) is cut into fixed blocks of `block` indices: the cut depends only on the range
// and the block size, never on the number of threads. A loop body sees whole blocks; a reduction computes
// one partial result per block and combines the partials in block order on the calling thread. So every
// result, rounding included, is the same with 1, 2 or 16 threads (tests/cpp/parallel/parallel_for_test.cpp
// and the solver's thread tests check bit-identical output), and a range of at most one block runs on the
// caller exactly as a plain loop would.
//
// Choosing `block`: large enough that one block is worth a task (tens of microseconds of work: about
// 256-2048 rows of the solver's n x 3 kernels) and small enough to give every thread several blocks.
// Blocks are claimed dynamically, so uneven blocks balance themselves.
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

#include "core/parallel/thread_pool.h"

namespace sd::parallel {

// Number of fixed blocks of `block` indices covering [begin, end).
inline int block_count(int begin, int end, int block) {
  if (end <= begin) return 0;
  const long long n = static_cast<long long>(end) - begin;
  const long long b = std::max(block, 1);
  return static_cast<int>((n + b - 1) / b);
}

// body(lo, hi) for the blocks [lo, hi) of [begin, end), in parallel. Blocks must write disjoint outputs.
template <typename Body>
void parallel_for(int begin, int end, int block, Body&& body) {
  const int blocks = block_count(begin, end, block);
  block = std::max(block, 1);
  if (blocks == 1) {
    body(begin, end);
    return;
  }
  run_tasks(blocks, [&](int b) {
    const int lo = begin + b * block;
    body(lo, std::min(end, lo + block));
  });
}

// combine(... combine(combine(init, map(block 0)), map(block 1)) ..., map(last block)), the maps in
// parallel and the combination in block order, so the result does not depend on the thread count.
// map(lo, hi) returns a T; combine(T&& accumulated, T&& partial) returns the new T.
template <typename T, typename Map, typename Combine>
T parallel_reduce(int begin, int end, int block, T init, Map&& map, Combine&& combine) {
  const int blocks = block_count(begin, end, block);
  block = std::max(block, 1);
  if (blocks == 0) return init;
  if (blocks == 1) return combine(std::move(init), map(begin, end));
  std::vector<T> partial(static_cast<std::size_t>(blocks));
  run_tasks(blocks, [&](int b) {
    const int lo = begin + b * block;
    partial[static_cast<std::size_t>(b)] = map(lo, std::min(end, lo + block));
  });
  T result = std::move(init);
  for (T& p : partial) result = combine(std::move(result), std::move(p));
  return result;
}

// The sum of map(lo, hi) over the blocks, in block order (the common reduction).
template <typename Map>
double parallel_sum(int begin, int end, int block, Map&& map) {
  return parallel_reduce(begin, end, block, 0.0, std::forward<Map>(map), [](double a, double b) { return a + b; });
}

}  // namespace sd::parallel
