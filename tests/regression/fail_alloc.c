// Test helper, loaded with LD_PRELOAD: heap allocations of this process fail as they do when memory is
// exhausted (NULL and ENOMEM, so that C++'s operator new throws std::bad_alloc): every one of at least
// MOTE_FAIL_ALLOC_AT_LEAST bytes, and every one of exactly MOTE_FAIL_ALLOC_OF bytes (issue 22: rank 0
// out of memory while it builds a file; mpi_memory_faults.py). Unset, nothing fails.
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

void* __libc_malloc(size_t size);
void* __libc_calloc(size_t count, size_t size);
void* __libc_realloc(void* old, size_t size);
void* __libc_memalign(size_t alignment, size_t size);

static size_t fail_at_least = SIZE_MAX;
static size_t fail_of = 0;

static size_t size_from_environment(const char* name, size_t otherwise) {
  const char* text = getenv(name);
  return text && *text ? (size_t)strtoull(text, NULL, 10) : otherwise;
}

__attribute__((constructor)) static void read_limits(void) {
  fail_at_least = size_from_environment("MOTE_FAIL_ALLOC_AT_LEAST", SIZE_MAX);
  fail_of = size_from_environment("MOTE_FAIL_ALLOC_OF", 0);
}

static int refused(size_t size) {
  if (size < fail_at_least && (fail_of == 0 || size != fail_of)) return 0;
  errno = ENOMEM;
  return 1;
}

void* malloc(size_t size) { return refused(size) ? NULL : __libc_malloc(size); }

void* calloc(size_t count, size_t size) {
  if (size != 0 && count > SIZE_MAX / size) {
    errno = ENOMEM;
    return NULL;
  }
  return refused(count * size) ? NULL : __libc_calloc(count, size);
}

void* realloc(void* old, size_t size) { return refused(size) ? NULL : __libc_realloc(old, size); }

void* memalign(size_t alignment, size_t size) { return refused(size) ? NULL : __libc_memalign(alignment, size); }

void* aligned_alloc(size_t alignment, size_t size) { return memalign(alignment, size); }

int posix_memalign(void** out, size_t alignment, size_t size) {
  if (refused(size)) return ENOMEM;
  void* p = __libc_memalign(alignment, size);
  if (!p) return ENOMEM;
  *out = p;
  return 0;
}
