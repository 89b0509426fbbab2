#pragma once
/// @brief Element loops split over a few threads. Plain std::thread per call rather than
/// OpenMP: OpenMP's idle workers spin and steal the core the serial sparse factorisation needs.

#include <algorithm>
#include <cstddef>
#include <exception>
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

/// Calls task(i) for every i in [0, count), each on a thread of its own, and rethrows the first
/// exception a task threw once all have ended. For a few large independent jobs (the ligaments
/// of a knee) whose serial parts (a sparse factorisation) leave cores idle.
template <class Task> void parallel_tasks(std::size_t count, Task&& task)
{
  if (count <= 1) {
    if (count == 1)
      task(std::size_t{0});
    return;
  }
  std::vector<std::exception_ptr> errors(count);
  std::vector<std::thread> threads;
  for (std::size_t i = 1; i < count; ++i)
    threads.emplace_back([&, i] {
      try {
        task(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    });
  try {
    task(std::size_t{0});
  } catch (...) {
    errors[0] = std::current_exception();
  }
  for (std::thread& thread : threads)
    thread.join();
  for (const std::exception_ptr& error : errors)
    if (error)
      std::rethrow_exception(error);
}

} // namespace ligsim::sim
