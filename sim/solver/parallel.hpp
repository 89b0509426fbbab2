#pragma once
/// @brief Element loops split over a few threads. Plain std::thread per call rather than
/// OpenMP: OpenMP's idle workers spin and steal the core the serial sparse factorisation needs.

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace ligsim::sim {

/// Threads used for element loops (the hardware's, at most 8).
inline int worker_count()
{
  static const int count = std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 8);
  return count;
}

/// Calls body(begin, end, worker) on `worker_count()` contiguous slices of [0, count), in
/// parallel when count is large enough to pay for the threads. Workers are numbered from 0.
template <class Body> void parallel_slices(std::ptrdiff_t count, Body&& body)
{
  constexpr std::ptrdiff_t min_per_worker = 2048;
  const int workers =
      static_cast<int>(std::min<std::ptrdiff_t>(worker_count(), count / min_per_worker));
  if (workers <= 1) {
    body(std::ptrdiff_t{0}, count, 0);
    return;
  }
  std::vector<std::thread> threads;
  for (int w = 1; w < workers; ++w)
    threads.emplace_back([&, w] { body(count * w / workers, count * (w + 1) / workers, w); });
  body(std::ptrdiff_t{0}, count / workers, 0);
  for (std::thread& thread : threads)
    thread.join();
}

} // namespace ligsim::sim
