#pragma once
// One background task at a time (packing, opening, exporting) for aggpack-gui: runs on a worker
// thread so the window stays live, reports progress through atomics, and can be cancelled.

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "aggpack/pack/packing.h"
#include "aggpack/render/renderer.h"
#include "library_words.h"

#ifdef AGGPACK_HAS_TBB
#include <tbb/task_scheduler_observer.h>
#endif

namespace aggpack::gui {

/// Lowers the calling thread's scheduling priority (Linux: nice is per thread) to the window
/// thread's nice + 10, so a job that keeps every core busy leaves the window thread and the X
/// server the CPU when they need it. Without it a large pack on 2 cores stalled a buffer swap for
/// 145 ms. Best effort: a failure leaves the priority as it was.
void lower_thread_priority();

#ifdef AGGPACK_HAS_TBB
/// Lowers the priority of every TBB worker thread as it starts work (the job's parallel loops run
/// on them). The window thread's own parallel loops run on it at its own priority, helped by the
/// workers.
class WorkerPriority : public tbb::task_scheduler_observer {
 public:
  WorkerPriority() { observe(true); }
  ~WorkerPriority() override { observe(false); }
  WorkerPriority(const WorkerPriority&) = delete;
  WorkerPriority& operator=(const WorkerPriority&) = delete;
  void on_scheduler_entry(bool is_worker) override {
    if (is_worker) lower_thread_priority();
  }
};
#endif

/// What a finished job hands back to the window thread.
struct JobResult {
  bool is_ok = false;
  std::string message;                     ///< status line: summary or error
  std::shared_ptr<const Packing> packing;  ///< new packing to show, or null (export)
  /// The packing's scene, built on the worker (prepare_scene) for the window to upload.
  std::shared_ptr<SceneData> scene;
  /// Open only: the configuration stored in the file, to fill the panel ("" = none).
  std::string config_toml;
};

class BackgroundJob {
 public:
  /// The task gets the job so it can publish progress and poll cancellation; it returns its
  /// result or throws (the error, in the window's language, becomes the status message).
  using Task = std::function<JobResult(BackgroundJob&)>;

  BackgroundJob() = default;
  ~BackgroundJob() { wait(); }
  BackgroundJob(const BackgroundJob&) = delete;
  BackgroundJob& operator=(const BackgroundJob&) = delete;

  /// Starts `task` on a worker thread. Precondition: !is_running().
  void start(std::string name, Task task) {
    wait();
    set_name(std::move(name));
    set_detail("");
    start_time_ = std::chrono::steady_clock::now();
    progress_ = 0.0;
    cancel_ = false;
    is_running_ = true;
    has_result_ = false;
    worker_ = std::thread([this, task = std::move(task)] {
      lower_thread_priority();
      JobResult result;
      try {
        result = task(*this);
      } catch (const std::exception& error) {
        result.is_ok = false;
        result.message = error_words(error);
      }
      {
        std::lock_guard lock(mutex_);
        result_ = std::move(result);
        has_result_ = true;
      }
      is_running_ = false;
    });
  }

  /// Takes the result of a finished job (once). Returns false while running or when taken.
  bool take_result(JobResult& out) {
    std::lock_guard lock(mutex_);
    if (!has_result_) return false;
    out = std::move(result_);
    has_result_ = false;
    if (worker_.joinable()) worker_.join();
    return true;
  }

  void wait() {
    if (worker_.joinable()) worker_.join();
  }

  [[nodiscard]] bool is_running() const { return is_running_; }
  /// A finished job's result that take_result has not taken yet.
  [[nodiscard]] bool has_result() const {
    std::lock_guard lock(mutex_);
    return has_result_;
  }
  /// What the job does now ("Packing", then "Building the scene"); the task may change it.
  [[nodiscard]] std::string name() const {
    std::lock_guard lock(mutex_);
    return name_;
  }
  void set_name(std::string name) {
    std::lock_guard lock(mutex_);
    name_ = std::move(name);
  }
  /// Seconds since the job started.
  [[nodiscard]] double elapsed_seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time_).count();
  }
  /// Fraction done in [0, 1] (set by the task).
  [[nodiscard]] double progress() const { return progress_; }
  void set_progress(double fraction) { progress_ = fraction; }
  void request_cancel() { cancel_ = true; }
  /// The flag packers poll (PackControl::cancel).
  [[nodiscard]] const std::atomic<bool>* cancel_flag() const { return &cancel_; }
  [[nodiscard]] bool is_cancel_requested() const { return cancel_; }
  /// Free-form progress text (e.g. "placed 512 of 1050"), set by the task.
  void set_detail(std::string detail) {
    std::lock_guard lock(mutex_);
    detail_ = std::move(detail);
  }
  [[nodiscard]] std::string detail() const {
    std::lock_guard lock(mutex_);
    return detail_;
  }

 private:
#ifdef AGGPACK_HAS_TBB
  WorkerPriority worker_priority_;
#endif
  std::thread worker_;
  std::string name_;
  std::chrono::steady_clock::time_point start_time_ = std::chrono::steady_clock::now();
  std::atomic<double> progress_{0.0};
  std::atomic<bool> cancel_{false};
  std::atomic<bool> is_running_{false};
  mutable std::mutex mutex_;
  bool has_result_ = false;
  JobResult result_;
  std::string detail_;
};

}  // namespace aggpack::gui
