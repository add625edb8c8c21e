#pragma once
// Heap allocation counter for tests that check a cycle allocates nothing. Include it in exactly one
// file of a test program: it replaces malloc, calloc, realloc and operator new/delete for the
// whole program (Eigen allocates through std::malloc, not operator new). Set g_allocations = 0 and
// g_counting = true around the code under test, then read g_allocations.
#include <cstdlib>
#include <new>

extern "C" void* __libc_malloc(std::size_t);
extern "C" void* __libc_calloc(std::size_t, std::size_t);
extern "C" void* __libc_realloc(void*, std::size_t);
extern "C" void __libc_free(void*);
namespace {
bool g_counting = false;
long g_allocations = 0;
void count() {
  if (g_counting) ++g_allocations;
}
}  // namespace
extern "C" void* malloc(std::size_t size) {
  count();
  return __libc_malloc(size);
}
extern "C" void* calloc(std::size_t n, std::size_t size) {
  count();
  return __libc_calloc(n, size);
}
extern "C" void* realloc(void* p, std::size_t size) {
  count();
  return __libc_realloc(p, size);
}
void* operator new(std::size_t size) {
  count();
  if (void* p = __libc_malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { __libc_free(p); }
void operator delete[](void* p) noexcept { __libc_free(p); }
void operator delete(void* p, std::size_t) noexcept { __libc_free(p); }
void operator delete[](void* p, std::size_t) noexcept { __libc_free(p); }

