// BackgroundJob's thread priority (Linux: nice is per thread, set through the thread's id).

#include "background_job.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace aggpack::gui {

void lower_thread_priority() {
  constexpr int kNicer = 10;
  // The window thread is the process's main thread: PRIO_PROCESS with the process id reads its
  // nice value (getpriority returns -1 for nice -1 too, hence errno).
  errno = 0;
  const int window_nice = getpriority(PRIO_PROCESS, static_cast<id_t>(getpid()));
  if (errno != 0) return;
  const auto thread = static_cast<id_t>(syscall(SYS_gettid));
  errno = 0;
  const int current = getpriority(PRIO_PROCESS, thread);
  if (errno != 0) return;
  const int wanted = std::min(19, window_nice + kNicer);
  if (current < wanted) (void)setpriority(PRIO_PROCESS, thread, wanted);
}

}  // namespace aggpack::gui
