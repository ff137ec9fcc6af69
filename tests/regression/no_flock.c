// Test helper, loaded with LD_PRELOAD: flock(2) on a file named run.lock fails with ENOSYS, as on a
// file system without locks (some Lustre mounts), so that run_directories.py exercises the lock by
// the file's existence (src/io/run_directory.cpp). Every other flock goes to the C library.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static int names_run_lock(int fd) {
  char link[64], target[4096];
  snprintf(link, sizeof(link), "/proc/self/fd/%d", fd);
  const ssize_t n = readlink(link, target, sizeof(target) - 1);
  if (n < 0) return 0;
  target[n] = '\0';
  const size_t length = (size_t)n;
  return length >= 9 && strcmp(target + length - 9, "/run.lock") == 0;
}

int flock(int fd, int operation) {
  if (names_run_lock(fd)) {
    errno = ENOSYS;
    return -1;
  }
  int (*next)(int, int) = (int (*)(int, int))dlsym(RTLD_NEXT, "flock");
  return next(fd, operation);
}
