#include "aggpack/core/isolated.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <new>
#include <utility>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"

#ifdef AGGPACK_HAS_TBB
#include <tbb/global_control.h>
#endif

// Weak: defined only when a sanitizer runtime is linked in.
extern "C" void __sanitizer_set_death_callback(void (*callback)()) __attribute__((weak));

namespace aggpack {

namespace {

using Clock = std::chrono::steady_clock;

// One record per finished item, child to parent: this header, then `length` bytes (the result,
// or the exception's message).
struct RecordHeader {
  std::uint64_t item;
  std::uint64_t length;
  std::uint32_t is_done;
  std::uint32_t padding;
};

int default_workers() { return allowed_threads(); }

// Ends TBB's worker threads (they start again at the next parallel loop) before the parent
// forks. A worker that has just finished its part of a loop may still be freeing its task when
// the loop returns; a child forked at that moment inherits the allocator's lock taken. glibc's
// malloc guards against that at fork, GCC 12's sanitizer allocator does not. A sanitized CI run
// hung for ten minutes in `aggpack mesomodel` of a periodic box, whose TetGen worker is forked
// right after the parallel loop that measures the clipped pieces: most likely that way. Best
// effort: inside a parallel loop, or while another thread of the program uses TBB, finalize
// refuses and the workers stay.
void stop_thread_pool() {
#ifdef AGGPACK_HAS_TBB
  tbb::task_scheduler_handle handle{tbb::attach{}};
  (void)tbb::finalize(handle, std::nothrow);
#endif
}

std::shared_mutex& fork_mutex() {
  static std::shared_mutex mutex;
  return mutex;
}

bool write_all(int fd, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t written = ::write(fd, bytes, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    bytes += written;
    size -= static_cast<std::size_t>(written);
  }
  return true;
}

// The child's whole life: run its batch, stream each result, leave without running anything of
// the parent's (destructors, atexit handlers, stdio flushes).
[[noreturn]] void run_child(int fd, const std::vector<std::size_t>& items,
                            const std::function<std::string(std::size_t)>& work, pid_t parent) {
#ifdef __linux__
  // Die with the parent instead of computing for nobody.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
#endif
  if (::getppid() != parent) ::_exit(1);
  // A crash of the work is the child's death, nothing more: default actions for the fatal
  // signals (a sanitizer's or fuzzer's handler inherited from the parent would report it as the
  // parent's crash) and no sanitizer death callback (libFuzzer's saves the input as a finding).
  for (const int fatal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(fatal, SIG_DFL);
  if (&__sanitizer_set_death_callback != nullptr) __sanitizer_set_death_callback(nullptr);
  const int null = ::open("/dev/null", O_WRONLY);
  if (null >= 0) {
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    ::close(null);
  }
  for (const std::size_t item : items) {
    std::string bytes;
    std::uint32_t is_done = 1;
    try {
      bytes = work(item);
    } catch (const std::exception& error) {
      bytes = error.what();
      is_done = 0;
    } catch (...) {
      bytes = "an unknown exception";
      is_done = 0;
    }
    const RecordHeader header{item, bytes.size(), is_done, 0};
    if (!write_all(fd, &header, sizeof header) || !write_all(fd, bytes.data(), bytes.size())) {
      ::_exit(1);
    }
  }
  ::_exit(0);
}

Wording describe_status(int status) {
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    const char* name = ::strsignal(signal);
    return {Sentence::kWorkerSignal, {std::to_string(signal), name ? name : "?"}};
  }
  if (WIFEXITED(status)) return {Sentence::kWorkerExited, {std::to_string(WEXITSTATUS(status))}};
  return {Sentence::kWorkerStatus, {std::to_string(status)}};
}

struct Worker {
  pid_t pid = -1;
  int fd = -1;
  std::vector<std::size_t> items;
  std::size_t next = 0;  ///< items[next] is the one in progress
  std::string buffer;
  Clock::time_point item_start;
};

// The parent's side: hands batches to workers, collects records, replaces dead workers.
class Pool {
 public:
  Pool(std::size_t count, const std::function<std::string(std::size_t)>& work,
       const IsolatedOptions& options)
      : work_(work), options_(options), outcomes_(count) {
    const int workers = options.workers > 0 ? options.workers : default_workers();
    // Several batches per worker so that workers finish together; small enough that a crash
    // re-forks for few items, large enough that forking costs little.
    const std::size_t batch =
        std::clamp<std::size_t>(count / (4 * static_cast<std::size_t>(workers)), 1, 64);
    for (std::size_t begin = 0; begin < count; begin += batch) {
      std::vector<std::size_t> items;
      for (std::size_t i = begin; i < std::min(count, begin + batch); ++i) items.push_back(i);
      queue_.push_back(std::move(items));
    }
    max_workers_ = static_cast<std::size_t>(workers);
  }
  Pool(const Pool&) = delete;
  Pool& operator=(const Pool&) = delete;

  ~Pool() {
    for (Worker& worker : workers_) {
      if (worker.pid > 0) ::kill(worker.pid, SIGKILL);
      reap(worker);
    }
  }

  std::vector<IsolatedOutcome> run() {
    stop_thread_pool();
    while (!queue_.empty() || !workers_.empty()) {
      while (workers_.size() < max_workers_ && !queue_.empty()) {
        start(std::move(queue_.front()));
        queue_.pop_front();
      }
      wait_for_workers();
    }
    return std::move(outcomes_);
  }

 private:
  void start(std::vector<std::size_t> items) {
    int fds[2];
    if (::pipe(fds) != 0) {
      throw IoError(Wording{Sentence::kWorkerPipe, {std::strerror(errno)}});
    }
    const pid_t parent = ::getpid();
    // No ticker thread is formatting or printing while the child is made (section_without_fork).
    std::unique_lock no_sections(fork_mutex());
    const pid_t pid = ::fork();
    if (pid < 0) {
      const int error = errno;
      ::close(fds[0]);
      ::close(fds[1]);
      throw IoError(Wording{Sentence::kWorkerStart, {std::strerror(error)}});
    }
    if (pid == 0) {
      ::close(fds[0]);
      for (const Worker& other : workers_) ::close(other.fd);
      run_child(fds[1], items, work_, parent);
    }
    no_sections.unlock();
    ::close(fds[1]);
    Worker worker;
    worker.pid = pid;
    worker.fd = fds[0];
    worker.items = std::move(items);
    worker.item_start = Clock::now();
    workers_.push_back(std::move(worker));
  }

  void wait_for_workers() {
    std::vector<pollfd> polled(workers_.size());
    const auto now = Clock::now();
    const auto limit = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(options_.time_limit));
    auto wait = limit;
    for (std::size_t w = 0; w < workers_.size(); ++w) {
      polled[w] = {workers_[w].fd, POLLIN, 0};
      wait =
          std::min(wait, std::max(Clock::duration::zero(), workers_[w].item_start + limit - now));
    }
    const auto wait_ms = std::chrono::ceil<std::chrono::milliseconds>(wait).count();
    const int ready =
        ::poll(polled.data(), polled.size(), static_cast<int>(std::min<long long>(wait_ms, 60000)));
    if (ready < 0 && errno != EINTR) {
      throw IoError(Wording{Sentence::kWorkerWait, {std::strerror(errno)}});
    }
    // Backwards, so that removing a finished worker keeps the indices of those not yet visited.
    for (std::size_t w = workers_.size(); w-- > 0;) {
      Worker& worker = workers_[w];
      bool is_finished = false;
      if (ready > 0 && polled[w].revents != 0) is_finished = !read_from(worker);
      if (!is_finished && Clock::now() - worker.item_start > limit) {
        ::kill(worker.pid, SIGKILL);
        reap(worker);
        fail_current(worker, {Sentence::kWorkerTimedOut, {format_seconds(options_.time_limit)}});
        is_finished = true;
      } else if (is_finished) {
        const int status = reap(worker);
        if (worker.next < worker.items.size()) fail_current(worker, describe_status(status));
      }
      if (is_finished) workers_.erase(workers_.begin() + static_cast<std::ptrdiff_t>(w));
    }
  }

  // Reads what the worker sent; false at end of stream (the worker is done or dead).
  bool read_from(Worker& worker) {
    char chunk[1 << 16];
    ssize_t got = 0;
    do {
      got = ::read(worker.fd, chunk, sizeof chunk);
    } while (got < 0 && errno == EINTR);
    if (got <= 0) return false;
    worker.buffer.append(chunk, static_cast<std::size_t>(got));
    std::size_t used = 0;
    while (worker.buffer.size() - used >= sizeof(RecordHeader)) {
      RecordHeader header{};
      std::memcpy(&header, worker.buffer.data() + used, sizeof header);
      if (worker.buffer.size() - used - sizeof header < header.length) break;
      const char* bytes = worker.buffer.data() + used + sizeof header;
      IsolatedOutcome& outcome = outcomes_.at(header.item);
      outcome.is_done = header.is_done != 0;
      if (outcome.is_done) {
        outcome.bytes.assign(bytes, header.length);
      } else {
        outcome.failure_wording = {Sentence::kWorkerThrew, {std::string(bytes, header.length)}};
        outcome.failure = english(outcome.failure_wording);
      }
      used += sizeof header + header.length;
      ++worker.next;
      count_settled();
      worker.item_start = Clock::now();
    }
    worker.buffer.erase(0, used);
    return true;
  }

  // The item in progress failed: record why and queue the rest of the batch for a new worker.
  void fail_current(Worker& worker, const Wording& failure) {
    if (worker.next >= worker.items.size()) return;
    IsolatedOutcome& outcome = outcomes_[worker.items[worker.next]];
    outcome.failure = english(failure);
    outcome.failure_wording = failure;
    count_settled();
    std::vector<std::size_t> rest(
        worker.items.begin() + static_cast<std::ptrdiff_t>(worker.next) + 1, worker.items.end());
    if (!rest.empty()) queue_.push_front(std::move(rest));
  }

  void count_settled() {
    ++settled_;
    if (options_.on_settled) options_.on_settled(settled_, outcomes_.size());
  }

  static int reap(Worker& worker) {
    if (worker.fd >= 0) {
      ::close(worker.fd);
      worker.fd = -1;
    }
    int status = 0;
    if (worker.pid > 0) {
      while (::waitpid(worker.pid, &status, 0) < 0 && errno == EINTR) {
      }
      worker.pid = -1;
    }
    return status;
  }

  static std::string format_seconds(double seconds) {
    std::string text = std::to_string(seconds);
    text.erase(text.find_last_not_of('0') + 1);
    if (!text.empty() && text.back() == '.') text.pop_back();
    return text;
  }

  const std::function<std::string(std::size_t)>& work_;
  const IsolatedOptions& options_;
  std::vector<IsolatedOutcome> outcomes_;
  std::size_t settled_ = 0;
  std::deque<std::vector<std::size_t>> queue_;
  std::vector<Worker> workers_;
  std::size_t max_workers_ = 1;
};

}  // namespace

std::shared_lock<std::shared_mutex> section_without_fork() {
  return std::shared_lock(fork_mutex());
}

std::thread start_thread_before_forks(std::function<void()> body) {
  // Shared with the thread: it signals through it after this function may have returned.
  struct Start {
    std::mutex mutex;
    std::condition_variable is_running_changed;
    bool is_running = false;
  };
  const auto start = std::make_shared<Start>();
  std::thread thread([start, body = std::move(body)] {
    {
      const std::lock_guard lock(start->mutex);
      start->is_running = true;
    }
    start->is_running_changed.notify_one();
    body();
  });
  std::unique_lock lock(start->mutex);
  start->is_running_changed.wait(lock, [&start] { return start->is_running; });
  return thread;
}

std::vector<IsolatedOutcome> run_isolated(std::size_t count,
                                          const std::function<std::string(std::size_t)>& work,
                                          const IsolatedOptions& options) {
  if (options.workers < 0) {
    throw InvalidInput("worker processes", std::to_string(options.workers), ">= 0 (0 = threads)");
  }
  // A week at most keeps the deadline arithmetic far from overflowing.
  require_in_range("time limit (s)", options.time_limit, 1e-3, 7 * 24 * 3600.0);
  if (count == 0) return {};
  Pool pool(count, work, options);
  return pool.run();
}

}  // namespace aggpack
