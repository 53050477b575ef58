#include "aggpack/core/temp_paths.h"

#include <dirent.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <mutex>

namespace aggpack {

namespace {

constexpr int kSlots = 64;
enum SlotState : int { kFree = 0, kFilling = 1, kLiveFile = 2, kLiveFolder = 3 };

struct Slot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX];
};

Slot g_slots[kSlots];
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

// Removes the entries directly inside `path` and then the folder, with raw system calls only.
void remove_flat_folder(const char* path) {
  const int folder = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (folder >= 0) {
    alignas(8) char entries[4096];
    for (int pass = 0; pass < 1000; ++pass) {
      bool removed = false;
      ::lseek(folder, 0, SEEK_SET);
      for (;;) {
        const long bytes = ::syscall(SYS_getdents64, folder, entries, sizeof entries);
        if (bytes <= 0) break;
        for (long offset = 0; offset < bytes;) {
          // struct linux_dirent64: u64 ino, s64 off, u16 reclen, u8 type, char name[]
          unsigned short length = 0;
          std::memcpy(&length, entries + offset + 16, sizeof length);
          const char* name = entries + offset + 19;
          const bool is_dot =
              name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0'));
          if (!is_dot && ::unlinkat(folder, name, 0) == 0) removed = true;
          if (length == 0) break;
          offset += length;
        }
      }
      if (!removed) break;
    }
    ::close(folder);
  }
  ::rmdir(path);
}

std::atomic<bool> g_is_terminating{false};

void on_signal(int signal_number) {
  // Other threads keep running while this one cleans up; wait_if_terminating() keeps the main
  // thread from exiting normally (with a misleading "cannot write") before the signal kills it.
  g_is_terminating.store(true);
  const int saved_errno = errno;
  for (Slot& slot : g_slots) {
    const int state = slot.state.load(std::memory_order_acquire);
    if (state == kLiveFile) {
      ::unlink(slot.path);
    } else if (state == kLiveFolder) {
      remove_flat_folder(slot.path);
    }
  }
  // Die of the same signal, as if there had been no handler.
  struct sigaction action {};
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  ::sigaction(signal_number, &action, nullptr);
  errno = saved_errno;
  ::raise(signal_number);
  // Deliver it now rather than when the handler returns.
  sigset_t unblock;
  sigemptyset(&unblock);
  sigaddset(&unblock, signal_number);
  ::pthread_sigmask(SIG_UNBLOCK, &unblock, nullptr);
}

void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const int signal_number : kSignals) {
      struct sigaction previous {};
      if (::sigaction(signal_number, nullptr, &previous) != 0) continue;
      const bool is_default =
          (previous.sa_flags & SA_SIGINFO) == 0 && previous.sa_handler == SIG_DFL;
      if (!is_default) continue;  // ignored (nohup) or someone else's handler: leave it
      struct sigaction action {};
      action.sa_handler = on_signal;
      sigemptyset(&action.sa_mask);
      for (const int other : kSignals) sigaddset(&action.sa_mask, other);
      action.sa_flags = 0;
      ::sigaction(signal_number, &action, nullptr);
    }
  });
}

}  // namespace

void wait_if_terminating() {
  while (g_is_terminating.load()) ::pause();
}

std::string temporary_pattern(const std::string& folder) {
  std::string pattern = folder.empty() ? std::string(".") : folder;
  if (pattern.back() != '/') pattern += '/';
  return pattern + ".aggpack.tmp.XXXXXX";
}

int register_temporary(const std::string& path, bool is_folder) {
  install_handlers();
  if (path.size() >= PATH_MAX) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (g_slots[i].state.compare_exchange_strong(expected, kFilling, std::memory_order_acq_rel)) {
      std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
      g_slots[i].state.store(is_folder ? kLiveFolder : kLiveFile, std::memory_order_release);
      return i;
    }
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot < 0 || slot >= kSlots) return;
  g_slots[slot].state.store(kFree, std::memory_order_release);
}

static_assert(sizeof(sigset_t) <= sizeof(unsigned char[128]), "sigset_t does not fit");

CleanupSignalBlock::CleanupSignalBlock() {
  sigset_t block;
  sigemptyset(&block);
  for (const int signal_number : kSignals) sigaddset(&block, signal_number);
  sigset_t previous;
  ::pthread_sigmask(SIG_BLOCK, &block, &previous);
  std::memcpy(saved_, &previous, sizeof previous);
}

CleanupSignalBlock::~CleanupSignalBlock() {
  sigset_t previous;
  std::memcpy(&previous, saved_, sizeof previous);
  ::pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

}  // namespace aggpack
