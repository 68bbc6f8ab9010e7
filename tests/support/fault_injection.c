/* Fault injection for the kill tests (tests/pipeline/job_kill_test.cpp, docs/robustness.md):
 * an LD_PRELOAD library that counts the file-system calls that change something (creating or
 * opening a file for writing, renaming, linking, deleting, making a folder) under one folder and
 * kills the process with SIGKILL just before the N-th, as a crash, an OOM kill or a lost node
 * would stop it there.
 *   TW_FAULT_UNDER=/abs/folder   count only calls whose path lies under it (required)
 *   TW_FAULT_KILL_AT=N           SIGKILL before the N-th counted call (1-based; 0/unset: never)
 *   TW_FAULT_LOG=/abs/file       append "N call path" for every counted call (to list them)
 * Calls glibc makes inside itself (fopen's open) are not seen twice: they do not go through
 * the dynamic symbols interposed here. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static atomic_long counted;

/* Whether `path` (relative to `dirfd`) lies under TW_FAULT_UNDER. */
static int watched(int dirfd, const char* path) {
  const char* under = getenv("TW_FAULT_UNDER");
  if (!under || !*under || !path) return 0;
  char full[PATH_MAX * 2];
  if (path[0] == '/') {
    snprintf(full, sizeof full, "%s", path);
  } else {
    char base[PATH_MAX] = "";
    if (dirfd == AT_FDCWD) {
      if (!getcwd(base, sizeof base)) return 0;
    } else {
      char link[64];
      snprintf(link, sizeof link, "/proc/self/fd/%d", dirfd);
      const ssize_t n = readlink(link, base, sizeof base - 1);
      if (n <= 0) return 0;
      base[n] = '\0';
    }
    snprintf(full, sizeof full, "%s/%s", base, path);
  }
  const size_t n = strlen(under);
  return strncmp(full, under, n) == 0 && (full[n] == '/' || full[n] == '\0');
}

/* Counts one call; dies at the chosen one. */
static void step(const char* call, int dirfd, const char* path) {
  if (!watched(dirfd, path)) return;
  const long n = atomic_fetch_add(&counted, 1) + 1;
  const char* log = getenv("TW_FAULT_LOG");
  if (log && *log) {
    static int (*real_open)(const char*, int, ...);
    if (!real_open) real_open = (int (*)(const char*, int, ...))dlsym(RTLD_NEXT, "open");
    const int fd = real_open(log, O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd >= 0) {
      dprintf(fd, "%ld %s %s\n", n, call, path);
      close(fd);
    }
  }
  const char* at = getenv("TW_FAULT_KILL_AT");
  if (at && atol(at) == n) raise(SIGKILL);
}

/* The next definition of `name` (glibc's), looked up once. */
#define REAL(name)                      \
  static __typeof__(&name) real_##name; \
  if (!real_##name) real_##name = (__typeof__(&name))dlsym(RTLD_NEXT, #name)

static int writes(int flags) {
  return (flags & (O_WRONLY | O_RDWR | O_CREAT | O_TRUNC)) != 0;
}
static int writes_mode(const char* mode) {
  return mode && (strchr(mode, 'w') || strchr(mode, 'a') || strchr(mode, '+'));
}

// The optional mode argument of open(2): read only when the flags create a file.
#define CREATION_MODE(mode, flags)       \
  mode_t mode = 0;                       \
  if ((flags) & (O_CREAT | O_TMPFILE)) { \
    va_list args;                        \
    va_start(args, flags);               \
    mode = va_arg(args, mode_t);         \
    va_end(args);                        \
  }

#define OPEN_LIKE(name)                             \
  int name(const char* path, int flags, ...) {      \
    REAL(name);                                     \
    CREATION_MODE(mode, flags)                      \
    if (writes(flags)) step(#name, AT_FDCWD, path); \
    return real_##name(path, flags, mode);          \
  }
OPEN_LIKE(open)
OPEN_LIKE(open64)

#define OPENAT_LIKE(name)                                 \
  int name(int dirfd, const char* path, int flags, ...) { \
    REAL(name);                                           \
    CREATION_MODE(mode, flags)                            \
    if (writes(flags)) step(#name, dirfd, path);          \
    return real_##name(dirfd, path, flags, mode);         \
  }
OPENAT_LIKE(openat)
OPENAT_LIKE(openat64)

int creat(const char* path, mode_t mode) {
  REAL(creat);
  step("creat", AT_FDCWD, path);
  return real_creat(path, mode);
}
int creat64(const char* path, mode_t mode) {
  REAL(creat64);
  step("creat64", AT_FDCWD, path);
  return real_creat64(path, mode);
}
FILE* fopen(const char* path, const char* mode) {
  REAL(fopen);
  if (writes_mode(mode)) step("fopen", AT_FDCWD, path);
  return real_fopen(path, mode);
}
FILE* fopen64(const char* path, const char* mode) {
  REAL(fopen64);
  if (writes_mode(mode)) step("fopen64", AT_FDCWD, path);
  return real_fopen64(path, mode);
}
int rename(const char* from, const char* to) {
  REAL(rename);
  step("rename", AT_FDCWD, to);
  return real_rename(from, to);
}
int renameat(int fromfd, const char* from, int tofd, const char* to) {
  REAL(renameat);
  step("renameat", tofd, to);
  return real_renameat(fromfd, from, tofd, to);
}
int renameat2(int fromfd, const char* from, int tofd, const char* to, unsigned flags) {
  REAL(renameat2);
  step("renameat2", tofd, to);
  return real_renameat2(fromfd, from, tofd, to, flags);
}
int link(const char* from, const char* to) {
  REAL(link);
  step("link", AT_FDCWD, to);
  return real_link(from, to);
}
int linkat(int fromfd, const char* from, int tofd, const char* to, int flags) {
  REAL(linkat);
  step("linkat", tofd, to);
  return real_linkat(fromfd, from, tofd, to, flags);
}
int symlink(const char* target, const char* path) {
  REAL(symlink);
  step("symlink", AT_FDCWD, path);
  return real_symlink(target, path);
}
int unlink(const char* path) {
  REAL(unlink);
  step("unlink", AT_FDCWD, path);
  return real_unlink(path);
}
int unlinkat(int dirfd, const char* path, int flags) {
  REAL(unlinkat);
  step("unlinkat", dirfd, path);
  return real_unlinkat(dirfd, path, flags);
}
int rmdir(const char* path) {
  REAL(rmdir);
  step("rmdir", AT_FDCWD, path);
  return real_rmdir(path);
}
int remove(const char* path) {
  REAL(remove);
  step("remove", AT_FDCWD, path);
  return real_remove(path);
}
int mkdir(const char* path, mode_t mode) {
  REAL(mkdir);
  step("mkdir", AT_FDCWD, path);
  return real_mkdir(path, mode);
}
int mkdirat(int dirfd, const char* path, mode_t mode) {
  REAL(mkdirat);
  step("mkdirat", dirfd, path);
  return real_mkdirat(dirfd, path, mode);
}
int truncate(const char* path, off_t length) {
  REAL(truncate);
  step("truncate", AT_FDCWD, path);
  return real_truncate(path, length);
}
