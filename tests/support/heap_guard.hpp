// Proof that code does not touch the heap: counters of every allocation and release the test
// executable makes, and a scope that also turns Eigen's own runtime check on.
//
//   In exactly one .cpp of the executable, before including this header:
//     #define EIGEN_RUNTIME_NO_MALLOC          // before any Eigen header (optional)
//     #define GYRO_HEAP_GUARD_IMPLEMENTATION   // the operator new replacement lives there
//   then, anywhere:
//     const gyro::test::HeapUse use = gyro::test::measure_heap([&] { /* code under test */ });
//     EXPECT_EQ(use.allocations, 0U);
//
// What is counted:
//   - operator new / new[] / delete / delete[] in every standard form (sized, aligned,
//     nothrow): a global replacement, so every caller in the process is seen;
//   - malloc, calloc, realloc and free called from the executable's own object files (where
//     the header-only library and Eigen are compiled; Eigen allocates with std::malloc, not
//     operator new), when compiled with GYRO_HEAP_GUARD_WRAP_MALLOC and linked with
//     -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free (see tests/CMakeLists.txt).
// measure_heap() additionally calls Eigen::internal::set_is_malloc_allowed(false) when
// EIGEN_RUNTIME_NO_MALLOC is defined: a dynamic Eigen allocation then fails Eigen's assert
// (so build without NDEBUG).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(EIGEN_RUNTIME_NO_MALLOC)
#include <Eigen/Core>
#endif

namespace gyro::test {

struct HeapUse {
  std::size_t allocations = 0;  // operator new, malloc, calloc, realloc calls
  std::size_t releases = 0;     // operator delete, free calls (of a non-null pointer)
};

namespace heap_guard_detail {
inline std::atomic<std::size_t> g_allocations{0};
inline std::atomic<std::size_t> g_releases{0};
inline void count_allocation() noexcept { g_allocations.fetch_add(1, std::memory_order_relaxed); }
inline void count_release() noexcept { g_releases.fetch_add(1, std::memory_order_relaxed); }
}  // namespace heap_guard_detail

// Counts what happens between its construction and used().
class HeapCounter {
 public:
  HeapCounter() noexcept
      : allocations0_(heap_guard_detail::g_allocations.load(std::memory_order_relaxed)),
        releases0_(heap_guard_detail::g_releases.load(std::memory_order_relaxed)) {}
  [[nodiscard]] HeapUse used() const noexcept {
    HeapUse u;
    u.allocations = heap_guard_detail::g_allocations.load(std::memory_order_relaxed) - allocations0_;
    u.releases = heap_guard_detail::g_releases.load(std::memory_order_relaxed) - releases0_;
    return u;
  }

 private:
  std::size_t allocations0_;
  std::size_t releases0_;
};

#if defined(EIGEN_RUNTIME_NO_MALLOC)
// While alive, a dynamic Eigen allocation fails Eigen's assertion.
class EigenMallocBan {
 public:
  EigenMallocBan() noexcept : was_allowed_(Eigen::internal::is_malloc_allowed()) {
    Eigen::internal::set_is_malloc_allowed(false);
  }
  ~EigenMallocBan() { Eigen::internal::set_is_malloc_allowed(was_allowed_); }
  EigenMallocBan(const EigenMallocBan&) = delete;
  EigenMallocBan& operator=(const EigenMallocBan&) = delete;

 private:
  bool was_allowed_;
};
#endif

// Runs f() with Eigen's heap banned (when EIGEN_RUNTIME_NO_MALLOC) and returns what it took
// from the heap. Keep gtest assertions out of f: a failing one allocates its message.
template <typename F>
[[nodiscard]] HeapUse measure_heap(F&& f) {
#if defined(EIGEN_RUNTIME_NO_MALLOC)
  const EigenMallocBan ban;
#endif
  const HeapCounter counter;
  f();
  return counter.used();
}

}  // namespace gyro::test

#if defined(GYRO_HEAP_GUARD_IMPLEMENTATION)

#if defined(GYRO_HEAP_GUARD_WRAP_MALLOC)
extern "C" {
void* __real_malloc(std::size_t size);
void* __real_calloc(std::size_t count, std::size_t size);
void* __real_realloc(void* ptr, std::size_t size);
void __real_free(void* ptr);

void* __wrap_malloc(std::size_t size) {
  gyro::test::heap_guard_detail::count_allocation();
  return __real_malloc(size);
}
void* __wrap_calloc(std::size_t count, std::size_t size) {
  gyro::test::heap_guard_detail::count_allocation();
  return __real_calloc(count, size);
}
void* __wrap_realloc(void* ptr, std::size_t size) {
  gyro::test::heap_guard_detail::count_allocation();
  return __real_realloc(ptr, size);
}
void __wrap_free(void* ptr) {
  if (ptr != nullptr) gyro::test::heap_guard_detail::count_release();
  __real_free(ptr);
}
}
#endif

namespace gyro::test::heap_guard_detail {

// The C library's allocator, past the wrappers (operator new is counted on its own).
inline void* raw_malloc(std::size_t size) noexcept {
#if defined(GYRO_HEAP_GUARD_WRAP_MALLOC)
  return __real_malloc(size);
#else
  return std::malloc(size);
#endif
}
inline void raw_free(void* ptr) noexcept {
#if defined(GYRO_HEAP_GUARD_WRAP_MALLOC)
  __real_free(ptr);
#else
  std::free(ptr);
#endif
}

inline void* allocate(std::size_t size) noexcept {
  count_allocation();
  return raw_malloc(size == 0 ? 1 : size);
}
inline void* allocate_aligned(std::size_t size, std::align_val_t alignment) noexcept {
  count_allocation();
  const std::size_t align = static_cast<std::size_t>(alignment);
  const std::size_t rounded = ((size == 0 ? 1 : size) + align - 1) / align * align;
  return std::aligned_alloc(align, rounded);  // released by free(): raw_free
}
inline void release(void* ptr) noexcept {
  if (ptr == nullptr) return;
  count_release();
  raw_free(ptr);
}
[[noreturn]] inline void out_of_memory() {
#if defined(__cpp_exceptions)
  throw std::bad_alloc();
#else
  std::abort();
#endif
}

}  // namespace gyro::test::heap_guard_detail

// The replaceable global allocation functions ([new.delete]): the eight allocation forms and
// the twelve deallocation forms.
void* operator new(std::size_t size) {
  void* p = gyro::test::heap_guard_detail::allocate(size);
  if (p == nullptr) gyro::test::heap_guard_detail::out_of_memory();
  return p;
}
void* operator new[](std::size_t size) {
  void* p = gyro::test::heap_guard_detail::allocate(size);
  if (p == nullptr) gyro::test::heap_guard_detail::out_of_memory();
  return p;
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return gyro::test::heap_guard_detail::allocate(size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return gyro::test::heap_guard_detail::allocate(size);
}
void* operator new(std::size_t size, std::align_val_t alignment) {
  void* p = gyro::test::heap_guard_detail::allocate_aligned(size, alignment);
  if (p == nullptr) gyro::test::heap_guard_detail::out_of_memory();
  return p;
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
  void* p = gyro::test::heap_guard_detail::allocate_aligned(size, alignment);
  if (p == nullptr) gyro::test::heap_guard_detail::out_of_memory();
  return p;
}
void* operator new(std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return gyro::test::heap_guard_detail::allocate_aligned(size, alignment);
}
void* operator new[](std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return gyro::test::heap_guard_detail::allocate_aligned(size, alignment);
}
void operator delete(void* ptr) noexcept { gyro::test::heap_guard_detail::release(ptr); }
void operator delete[](void* ptr) noexcept { gyro::test::heap_guard_detail::release(ptr); }
void operator delete(void* ptr, std::size_t) noexcept { gyro::test::heap_guard_detail::release(ptr); }
void operator delete[](void* ptr, std::size_t) noexcept { gyro::test::heap_guard_detail::release(ptr); }
void operator delete(void* ptr, const std::nothrow_t&) noexcept { gyro::test::heap_guard_detail::release(ptr); }
void operator delete[](void* ptr, const std::nothrow_t&) noexcept { gyro::test::heap_guard_detail::release(ptr); }
void operator delete(void* ptr, std::align_val_t) noexcept { gyro::test::heap_guard_detail::release(ptr); }
void operator delete[](void* ptr, std::align_val_t) noexcept { gyro::test::heap_guard_detail::release(ptr); }
void operator delete(void* ptr, std::size_t, std::align_val_t) noexcept {
  gyro::test::heap_guard_detail::release(ptr);
}
void operator delete[](void* ptr, std::size_t, std::align_val_t) noexcept {
  gyro::test::heap_guard_detail::release(ptr);
}
void operator delete(void* ptr, std::align_val_t, const std::nothrow_t&) noexcept {
  gyro::test::heap_guard_detail::release(ptr);
}
void operator delete[](void* ptr, std::align_val_t, const std::nothrow_t&) noexcept {
  gyro::test::heap_guard_detail::release(ptr);
}

#endif  // GYRO_HEAP_GUARD_IMPLEMENTATION
