#include "encoder/io/signal_cleanup.h"

#include <fcntl.h>
#include <unistd.h>
#if defined(__linux__)
#include <sys/syscall.h>
#endif

#include <cstddef>
#include <cstring>

namespace dcurve {
namespace {

// What the handler removes: fixed buffers and flags, the only state it may read safely.
struct Registered {
  char path[4096];
  volatile sig_atomic_t active = 0;
};
Registered g_file, g_folder;
const int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};

bool set(Registered* r, const std::string& path) {
  SignalBlock block;
  r->active = 0;
  if (path.empty()) return true;
  if (path.size() >= sizeof r->path) return false;
  std::memcpy(r->path, path.c_str(), path.size() + 1);
  r->active = 1;
  return true;
}

// Unlinks every entry of the folder with raw getdents64 (readdir is not async-signal-safe),
// then the folder. Elsewhere than Linux only an empty folder goes.
void empty_and_remove_folder(const char* path) {
#if defined(__linux__)
  const int fd = open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd >= 0) {
    alignas(8) char buffer[4096];
    long n;
    while ((n = syscall(SYS_getdents64, fd, buffer, sizeof buffer)) > 0) {
      for (long at = 0; at < n;) {
        // struct linux_dirent64: ino (8), off (8), reclen (2), type (1), name
        unsigned short reclen;
        std::memcpy(&reclen, buffer + at + 16, sizeof reclen);
        const char* name = buffer + at + 19;
        if (std::strcmp(name, ".") != 0 && std::strcmp(name, "..") != 0) unlinkat(fd, name, 0);
        at += reclen;
      }
    }
    close(fd);
  }
#endif
  rmdir(path);
}

void on_signal(int sig) {
  if (g_file.active) unlink(g_file.path);
  if (g_folder.active) empty_and_remove_folder(g_folder.path);
  signal(sig, SIG_DFL);
  raise(sig);
}

}  // namespace

SignalBlock::SignalBlock() {
  sigset_t set;
  sigemptyset(&set);
  for (int s : kCleanupSignals) sigaddset(&set, s);
  pthread_sigmask(SIG_BLOCK, &set, &old_);
}

SignalBlock::~SignalBlock() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

bool set_temporary_file(const std::string& path) { return set(&g_file, path); }
void clear_temporary_file() { g_file.active = 0; }
bool set_temporary_folder(const std::string& path) { return set(&g_folder, path); }

void remove_temporary_on_signal() {
  for (int s : kCleanupSignals) {
    struct sigaction old;
    if (sigaction(s, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(s, &sa, nullptr);
  }
}

}  // namespace dcurve
