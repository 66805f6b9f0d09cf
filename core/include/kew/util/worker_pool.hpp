#pragma once
// A fixed set of threads that run the jobs of one call together with the calling thread
// (design §3.3): the pipeline hands it the zones with work in a batch. Jobs are taken in
// index order by whichever thread is free; run() returns when every job has finished.
// What a job computes must not depend on which thread runs it.

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace kew::util {

class WorkerPool {
 public:
  /// `threads` ≥ 1 in all, the calling thread included (1: run() works alone).
  explicit WorkerPool(std::size_t threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// Calls job(i) once for every i in [0, jobs), on this thread and the pool's, and
  /// returns when all have returned. Not reentrant. A job that throws ends the program.
  void run(std::size_t jobs, const std::function<void(std::size_t)>& job);

  std::size_t threads() const { return workers_.size() + 1; }

 private:
  void work_loop();
  void take_jobs();

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  const std::function<void(std::size_t)>* job_ = nullptr;
  std::size_t jobs_ = 0;
  std::atomic<std::size_t> next_{0};
  std::size_t busy_ = 0;          // workers inside take_jobs() for this generation
  std::uint64_t generation_ = 0;  // one per run()
  bool stopping_ = false;
};

}  // namespace kew::util
