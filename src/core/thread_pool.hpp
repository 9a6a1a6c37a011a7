#pragma once
// A fixed set of worker threads that run one indexed batch of tasks at a time: what the parallel
// reference filter (`--backend cpu`) splits its per-particle loops over. The caller's thread takes
// part, so a pool of N threads starts N - 1 workers, and a pool of 1 runs everything in the caller.
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace depthtrack {

// The threads `--backend cpu` uses: the hardware's, at least 1.
int hardware_threads();

class ThreadPool {
 public:
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()) + 1; }
  // Calls task(t, thread) for t = 0 .. tasks - 1, each exactly once, handed out in order to whichever
  // thread is free (thread: 0 .. size() - 1, the caller is 0; no two tasks run on one thread at once,
  // so per-thread scratch may be indexed by it); returns when all are done. The first exception a task
  // throws is rethrown here (the other tasks still run).
  void run(size_t tasks, const std::function<void(size_t task, int thread)>& task);
  // As run(), but the tasks are handed out only as they are released: producer runs on the caller's
  // thread and calls release() once per task, in order, when its input is ready (the workers start
  // on task t while the caller prepares t + 1); then the caller takes part in what is left. If the
  // producer throws, the tasks it did not release are dropped, and its exception is rethrown once the
  // released ones are done (before a task's).
  void run_as_released(size_t tasks, const std::function<void(const std::function<void()>& release)>& producer,
                       const std::function<void(size_t task, int thread)>& task);

 private:
  void start_batch(size_t tasks, size_t released, const std::function<void(size_t, int)>& task);
  void finish_batch();          // takes part, waits for the batch, rethrows a task's exception
  void work(int thread);        // a worker's loop
  void take_tasks(int thread);  // runs released tasks of the current batch until none is left

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_, done_, released_more_;
  const std::function<void(size_t, int)>* task_ = nullptr;
  size_t tasks_ = 0, next_ = 0, finished_ = 0, released_ = 0;
  unsigned batch_ = 0;  // counts batches, so a worker knows a new one from the one it finished
  bool stop_ = false;
  std::exception_ptr error_;
};

// How many contiguous ranges run_ranges splits n items into: one on a pool of one thread, else a few a
// thread (8, at most n), so that a thread the system delays (a shared machine) holds up only a small share.
size_t range_count(const ThreadPool& pool, size_t n);

// Calls f(range, first, last, thread) for each of range_count(pool, n) contiguous ranges [first, last)
// that cover [0, n) in order, on the pool's threads (thread as ThreadPool::run gives it).
template <typename F>
void run_ranges(ThreadPool& pool, size_t n, F&& f) {
  const size_t ranges = range_count(pool, n);
  pool.run(ranges, [&](size_t r, int thread) { f(r, n * r / ranges, n * (r + 1) / ranges, thread); });
}

}  // namespace depthtrack
