# Fails when a static library references the heap, exceptions or stdio/file I/O.
# Usage: cmake -DNM=<nm> -DARCHIVE=<lib.a> -P CheckCoreSymbols.cmake
execute_process(COMMAND ${NM} -C -u ${ARCHIVE} OUTPUT_VARIABLE undefined RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nm failed on ${ARCHIVE}")
endif()
set(forbidden
  "malloc" "calloc" "realloc" "free" "posix_memalign" "aligned_alloc"
  "operator new" "operator delete"
  "__cxa_throw" "__cxa_allocate_exception" "__cxa_begin_catch" "_Unwind_Resume"
  "fopen" "fclose" "fread" "fwrite" "fprintf" "printf" "puts" "fputs" "fputc" "putchar"
  "open" "read" "write" "close" "stdout" "stderr" "_impure_ptr" "std::cout" "std::cerr"
  "std::ios_base")
string(REPLACE "\n" ";" lines "${undefined}")
set(hits "")
foreach(line IN LISTS lines)
  string(STRIP "${line}" sym)
  string(REGEX REPLACE "^U " "" sym "${sym}")
  foreach(f IN LISTS forbidden)
    # Whole-name match, or a C++ operator/name followed by its argument list.
    if(sym STREQUAL f OR sym MATCHES "^${f}\\(" OR sym MATCHES "^${f}\\[\\]\\(")
      list(APPEND hits "${sym}")
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES hits)
if(hits)
  string(REPLACE ";" "\n  " pretty "${hits}")
  message(FATAL_ERROR "${ARCHIVE} references forbidden symbols:\n  ${pretty}")
endif()
message(STATUS "${ARCHIVE}: no heap, exception or I/O symbols")
