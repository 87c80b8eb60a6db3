# Per-ISA kernel translation units: the ISA flags go on those files only, so the
# rest of the build (and the shipped binary's baseline) stays plain x86-64/SSE2.
# The scalar copy is the readable reference the SIMD paths are tested against;
# `--isa auto` never picks it (every x86-64 has SSE2), so it is built for
# build time, not speed: -Og compiles its tile kernels in 15 CPU-seconds
# where -O3 took 92 (-O1 36, -O0 9 but slow enough to lengthen the tests),
# and rounds alike, since no -O level contracts or reorders floating point
# here (-ffp-contract=off). At -Og, GCC 12 inlines too little to see that a
# shader which reads no planes never reads its uninitialized plane array
# (-Wmaybe-uninitialized), a false alarm silenced for these files only.
set(QUADRA_FLAGS_scalar "$<$<CONFIG:Release>:-Og>"
    "$<$<CONFIG:Release>:-Wno-maybe-uninitialized>")
set(QUADRA_FLAGS_sse2 "-msse2")
set(QUADRA_FLAGS_avx2 "-mavx2;-mf16c")
# GCC 12's own avx512fintrin.h trips -W(maybe-)uninitialized (its _mm512_undefined_*
# idiom), a known false positive; silenced for this file only (clang, which
# builds the ASan and fuzz build, has neither the warning nor the idiom).
set(QUADRA_FLAGS_avx512
    "-mavx512f;-mavx512bw;-mavx512dq;-mavx512vl;-mavx2;-mf16c"
    "$<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>" "$<$<CXX_COMPILER_ID:GNU>:-Wno-uninitialized>")

# quadra_isa_sources(<out-var> <template.cpp.in> <kernel-name>) configures one
# copy of a kernel source per ISA and returns the generated file list.
function(quadra_isa_sources out_var template name)
  set(files)
  foreach(isa scalar sse2 avx2 avx512)
    set(QUADRA_ISA ${isa})
    set(file ${CMAKE_CURRENT_BINARY_DIR}/${name}_${isa}.cpp)
    configure_file(${template} ${file} @ONLY)
    set(options ${QUADRA_FLAGS_${isa}})
    if(options)
      set_source_files_properties(${file} PROPERTIES COMPILE_OPTIONS "${options}")
    endif()
    set_source_files_properties(${file} PROPERTIES SKIP_PRECOMPILE_HEADERS ON
                                SKIP_UNITY_BUILD_INCLUSION ON)
    list(APPEND files ${file})
  endforeach()
  set(${out_var} ${files} PARENT_SCOPE)
endfunction()
