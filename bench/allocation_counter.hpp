#pragma once
/// \file
/// Counts the heap allocations of the program that includes it: the global operator new (and its
/// nothrow form, which Catch2 and a sanitizer's runtime use) is replaced by malloc and a count,
/// so that a test or a benchmark can check that a call allocates nothing. Include it in exactly
/// one source file of a program: the replacements are the program's, not a library's. The array
/// and sized forms of the standard library call these.

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>

namespace allocation_counter {
/// Allocations made by operator new so far, in every thread.
inline std::atomic<long> allocations{0};
}  // namespace allocation_counter

void* operator new(std::size_t size) {
  allocation_counter::allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* memory = std::malloc(size == 0 ? 1 : size)) return memory;
#if defined(__cpp_exceptions)
  throw std::bad_alloc();
#else
  std::fputs("out of memory\n", stderr);  // built as a controller is, without exceptions
  std::abort();
#endif
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  allocation_counter::allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }
