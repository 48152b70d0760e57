# ctest check: fails if a firmware image contains a heap: malloc and friends, operator
# new/delete or _sbrk, whoever pulled them in (our code, Eigen, libstdc++ or newlib).
#   cmake -DNM=<arm-none-eabi-nm> -DELF=<image.elf> -P check_no_heap.cmake
execute_process(COMMAND ${NM} --defined-only ${ELF}
                OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NM} failed on ${ELF}")
endif()
# Whole symbol names: C allocator and newlib's reentrant versions, _sbrk, and the
# mangled operator new/delete (_Znwj, _Znaj, _ZdlPv, _ZdaPv and their overloads).
set(heap_regex
    "[ \t](malloc|free|calloc|realloc|memalign|aligned_alloc|posix_memalign|_malloc_r|_free_r|_calloc_r|_realloc_r|_memalign_r|_sbrk|_sbrk_r|_Znwj[A-Za-z0-9_]*|_Znaj[A-Za-z0-9_]*|_ZdlPv[A-Za-z0-9_]*|_ZdaPv[A-Za-z0-9_]*)\n")
string(REGEX MATCHALL "[^\n]*${heap_regex}" found "${symbols}\n")
if(found)
  string(REPLACE "\n" "" found "${found}")
  list(JOIN found "\n  " found)
  message(FATAL_ERROR "heap linked into ${ELF}:\n  ${found}\n"
                      "What references it: the Cross Reference Table in the image's .map file.")
endif()
message(STATUS "no heap in ${ELF}")
