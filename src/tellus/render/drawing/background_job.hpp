#pragma once
// One job at a time on a TBB worker, for a renderer's frame loop that must not block on it:
// start() runs `work` on a worker, ready() says without waiting that it finished, take() hands
// the result over with the worker's CPU time, wait() blocks until it finished (a CPU wait for
// the worker, never for the GPU). The clipmaps' texture updates and the stack renderer's octree
// selection use it. Not thread-safe itself: one thread (the render thread) drives it.
#include <atomic>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <utility>

#include <spdlog/spdlog.h>
#include <tbb/task_group.h>

#include "tellus/core/thread_cpu_clock.hpp"

namespace tellus {

template <class Result>
class BackgroundJob {
 public:
  // `who` names the job in the log line an exception in it prompts.
  explicit BackgroundJob(std::string who) : who_(std::move(who)) {}
  ~BackgroundJob() { wait(); }
  BackgroundJob(const BackgroundJob&) = delete;
  BackgroundJob& operator=(const BackgroundJob&) = delete;

  // A job was started and not taken yet.
  bool running() const { return state_ != nullptr; }
  // It finished (take() it).
  bool ready() const { return state_ && state_->done.load(std::memory_order_acquire); }

  // Starts `work` on a worker; one job at a time (call when !running()).
  void start(std::function<Result()> work) {
    auto state = std::make_shared<State>();
    state_ = state;
    tasks_->run([state, work = std::move(work)] {
      const double start = threadCpuSeconds();
      state->result = work();
      state->workerCpuMs = (threadCpuSeconds() - start) * 1e3;
      state->done.store(true, std::memory_order_release);
    });
  }
  // Blocks until the job in flight, if any, finished.
  void wait() {
    if (!tasks_) return;
    try {
      tasks_->wait();
    } catch (const std::exception& e) {
      spdlog::error("{}: a background job failed: {}", who_, e.what());
    }
  }
  // The finished job's result and its worker's CPU ms (call when ready()); nothing runs after.
  std::pair<Result, double> take() {
    std::pair<Result, double> out{std::move(state_->result), state_->workerCpuMs};
    state_.reset();
    return out;
  }
  // Forgets the job (waits for it first): a result gone stale.
  void discard() {
    wait();
    state_.reset();
  }

 private:
  struct State {
    Result result{};
    double workerCpuMs = 0.0;
    std::atomic<bool> done{false};
  };
  std::string who_;
  std::shared_ptr<State> state_;
  // A pointer: task_group's destructor may throw, a renderer's may not.
  std::unique_ptr<tbb::task_group> tasks_ = std::make_unique<tbb::task_group>();
};

}  // namespace tellus
