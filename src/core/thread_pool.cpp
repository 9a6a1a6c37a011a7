#include "core/thread_pool.hpp"

#include <sched.h>

#include <algorithm>
#include <depthtrack/error.hpp>
#include <string>

namespace depthtrack {

size_t range_count(const ThreadPool& pool, size_t n) {
  return pool.size() == 1 ? 1 : std::min(n, 8 * static_cast<size_t>(pool.size()));
}

int hardware_threads() {
  // The CPUs this process may run on (taskset, a container's cpuset), not every CPU of the machine, which
  // hardware_concurrency counts: more threads than those only take turns.
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof(allowed), &allowed) == 0 && CPU_COUNT(&allowed) > 0) return CPU_COUNT(&allowed);
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

ThreadPool::ThreadPool(int threads) {
  if (threads < 1) throw InputError("a thread pool needs at least 1 thread, got " + std::to_string(threads));
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this, i] { work(i); });
}

ThreadPool::~ThreadPool() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  start_.notify_all();
  for (auto& w : workers_) w.join();
}

void ThreadPool::run(size_t tasks, const std::function<void(size_t, int)>& task) {
  if (tasks == 0) return;
  start_batch(tasks, tasks, task);
  finish_batch();
}

void ThreadPool::run_as_released(size_t tasks,
                                 const std::function<void(const std::function<void()>& release)>& producer,
                                 const std::function<void(size_t, int)>& task) {
  if (tasks == 0) {
    producer([] {});
    return;
  }
  start_batch(tasks, 0, task);
  const auto release = [this] {
    {
      const std::lock_guard lock(mutex_);
      if (released_ < tasks_) ++released_;
    }
    released_more_.notify_all();
  };
  std::exception_ptr producer_error;
  try {
    producer(release);
  } catch (...) {
    producer_error = std::current_exception();
  }
  {
    const std::lock_guard lock(mutex_);
    tasks_ = released_;  // what was not released is not run
    if (finished_ == tasks_) done_.notify_all();
  }
  released_more_.notify_all();
  if (!producer_error) return finish_batch();
  try {
    finish_batch();
  } catch (...) {  // the producer's failure is the one reported
  }
  std::rethrow_exception(producer_error);
}

void ThreadPool::start_batch(size_t tasks, size_t released, const std::function<void(size_t, int)>& task) {
  {
    const std::lock_guard lock(mutex_);
    task_ = &task;
    tasks_ = tasks;
    released_ = released;
    next_ = 0;
    finished_ = 0;
    error_ = nullptr;
    ++batch_;
  }
  start_.notify_all();
}

void ThreadPool::finish_batch() {
  take_tasks(0);
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return finished_ == tasks_; });
  task_ = nullptr;
  if (error_) std::rethrow_exception(error_);
}

void ThreadPool::take_tasks(int thread) {
  std::unique_lock lock(mutex_);
  const unsigned batch = batch_;
  for (;;) {
    // Workers wait here for the producer's next release; the caller arrives once all are released.
    released_more_.wait(lock, [&] { return batch_ != batch || !task_ || next_ >= tasks_ || next_ < released_; });
    if (batch_ != batch || !task_ || next_ >= tasks_) return;
    const size_t t = next_++;
    const auto* task = task_;
    lock.unlock();
    std::exception_ptr error;
    try {
      (*task)(t, thread);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (error && !error_) error_ = error;
    if (++finished_ == tasks_) done_.notify_all();
  }
}

void ThreadPool::work(int thread) {
  unsigned seen = 0;
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      start_.wait(lock, [&] { return stop_ || batch_ != seen; });
      if (stop_) return;
      seen = batch_;
    }
    take_tasks(thread);
  }
}

}  // namespace depthtrack
