/* Counts the heap allocations of the process (malloc, calloc, realloc) for
 * alloc_failing_step.f90: definitions here take the place of the C library's in the
 * executable they are linked into and hand the calls on to glibc's own. */
#include <stddef.h>
extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);
long fsym_test_mallocs = 0;
void *malloc(size_t n) { ++fsym_test_mallocs; return __libc_malloc(n); }
void *calloc(size_t a, size_t b) { ++fsym_test_mallocs; return __libc_calloc(a, b); }
void *realloc(void *p, size_t n) { ++fsym_test_mallocs; return __libc_realloc(p, n); }
