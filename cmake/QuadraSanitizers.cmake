# Sanitizer builds (issue 4). QUADRA_SANITIZE is a GCC/Clang -fsanitize= list,
# e.g. "address,undefined" or "thread"; empty (the default) leaves the build
# untouched. Included before any target is defined, so the flags reach every
# object and link the project builds (engine, per-ISA kernels, CLI, tests).
# scripts/sanitize.sh is the documented way to use it.
set(QUADRA_SANITIZE "" CACHE STRING
    "Comma-separated -fsanitize= list (address,undefined | thread); empty = off")

if(QUADRA_SANITIZE)
  if(QUADRA_SANITIZE MATCHES "thread" AND QUADRA_SANITIZE MATCHES "address")
    message(FATAL_ERROR "QUADRA_SANITIZE: thread and address cannot be combined")
  endif()
  # Frame pointers keep the reports' stacks complete at any optimization level;
  # no recovery, so the first UB finding fails the test instead of scrolling by.
  add_compile_options(-fsanitize=${QUADRA_SANITIZE} -fno-omit-frame-pointer
                      -fno-sanitize-recover=all)
  # clang links a C program's UBSan runtime without the C++ type checks
  # (vptr, function), so a C program linking a C++ library instrumented with
  # them does not link (the C API's tests, an embedder's C program); clang
  # builds leave those two out.
  if(QUADRA_SANITIZE MATCHES "undefined" AND CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    add_compile_options(-fno-sanitize=vptr,function)
  endif()
  add_link_options(-fsanitize=${QUADRA_SANITIZE})
  message(STATUS "quadra: sanitizers ${QUADRA_SANITIZE}")
endif()

# Fuzz builds (QUADRA_FUZZ): libFuzzer's coverage feedback needs every object
# instrumented, the engine's included; only the fuzz targets link libFuzzer's
# main (-fsanitize=fuzzer, tests/fuzz/CMakeLists.txt).
if(QUADRA_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "QUADRA_FUZZ needs clang (libFuzzer); scripts/fuzz.sh sets it")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

# A sanitized static library references the sanitizer runtime, so whatever
# links it must link that runtime too, including an embedder that finds the
# installed package (the InstallAndFindPackage test): export the link flag.
function(quadra_sanitizer_link_interface target)
  if(QUADRA_SANITIZE)
    target_link_options(${target} INTERFACE -fsanitize=${QUADRA_SANITIZE})
  endif()
endfunction()
