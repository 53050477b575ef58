#pragma once
// The process-wide list of live temporary files and folders, removed if the process is stopped
// by SIGINT, SIGTERM or SIGHUP (the handler unlinks them, then re-raises the signal with its
// default action, so the exit status still says "killed by signal"). The handler is installed on
// the first registration, and only for signals whose action is the default (a signal the parent
// ignores, e.g. under nohup, stays ignored). Normal exits and exceptions clean up through the
// owners' destructors (AtomicFile, temporary folders); this list covers the signals.
//
// The handler is async-signal-safe: a fixed table of paths, unlink/unlinkat/rmdir/getdents only.
// A registered folder is removed with the files directly inside it (folders are flat).

#include <string>

namespace aggpack {

/// Short name for temporary entries, so that any legal destination name still fits NAME_MAX:
/// "<folder>/.aggpack.tmp.XXXXXX".
std::string temporary_pattern(const std::string& folder);

/// Registers a temporary file (or flat folder). Returns a slot for unregister_temporary(), or -1
/// if the table is full or the path too long (then it is not removed on a signal).
int register_temporary(const std::string& path, bool is_folder = false);

/// Forgets a slot (after the entry was renamed into place or removed). -1 is ignored.
void unregister_temporary(int slot);

/// If a cleanup signal is being handled (by another thread), waits for it to end the process.
/// For main() before it reports an error or returns: a temporary removed by the handler must not
/// turn into a normal exit with a misleading message.
void wait_if_terminating();

/// Blocks SIGINT, SIGTERM and SIGHUP in this thread while alive, so that creating a temporary
/// and registering it cannot be split by a signal.
class CleanupSignalBlock {
 public:
  CleanupSignalBlock();
  ~CleanupSignalBlock();
  CleanupSignalBlock(const CleanupSignalBlock&) = delete;
  CleanupSignalBlock& operator=(const CleanupSignalBlock&) = delete;

 private:
  unsigned char saved_[128];  // sigset_t without <signal.h> in the header
};

}  // namespace aggpack
