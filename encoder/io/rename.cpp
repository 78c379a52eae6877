#include "encoder/io/rename.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>

namespace dcurve {
namespace {

// Where renameat2 is missing: a file gets a hard link (link(2) never replaces), a folder
// a check then a rename (rename(2) of a folder replaces only an empty folder).
int no_replace_fallback(const char* from, const char* to) {
  struct stat st;
  if (lstat(from, &st) != 0) return -1;
  if (!S_ISDIR(st.st_mode) && link(from, to) == 0) return unlink(from);
  if (!S_ISDIR(st.st_mode) && errno != EPERM && errno != ENOTSUP) return -1;
  if (lstat(to, &st) == 0) {
    errno = EEXIST;
    return -1;
  }
  return std::rename(from, to);
}

}  // namespace

int rename_no_replace(const char* from, const char* to) {
#if defined(__linux__) && defined(RENAME_NOREPLACE)
  if (renameat2(AT_FDCWD, from, AT_FDCWD, to, RENAME_NOREPLACE) == 0) return 0;
  if (errno != EINVAL && errno != ENOSYS) return -1;
#endif
  return no_replace_fallback(from, to);
}

int rename_exchange(const char* a, const char* b) {
#if defined(__linux__) && defined(RENAME_EXCHANGE)
  if (renameat2(AT_FDCWD, a, AT_FDCWD, b, RENAME_EXCHANGE) == 0) return 0;
  if (errno == EINVAL || errno == ENOSYS) errno = ENOTSUP;
  return -1;
#elif defined(__APPLE__)
  return renamex_np(a, b, RENAME_SWAP);
#else
  (void)a, (void)b;
  errno = ENOTSUP;
  return -1;
#endif
}

}  // namespace dcurve
