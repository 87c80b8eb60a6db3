# Per-ISA kernel translation units: the ISA flags go on those files only, so the
# rest of the build (and the shipped binary's baseline) stays plain x86-64/SSE2.
set(QUADRA_FLAGS_sse2 "-msse2")
set(QUADRA_FLAGS_avx2 "-mavx2;-mf16c")
# GCC 12's own avx512fintrin.h trips -W(maybe-)uninitialized (its _mm512_undefined_*
# idiom), a known false positive; silenced for this file only.
set(QUADRA_FLAGS_avx512
    "-mavx512f;-mavx512bw;-mavx512dq;-mavx512vl;-mavx2;-mf16c;-Wno-maybe-uninitialized;-Wno-uninitialized")

# The ASan+UBSan build leaves the AVX2 copy of the kernels uninstrumented:
# GCC takes 7-9 CPU-minutes for each tile kernel instrumented so (542 s
# user for tile_kernel_avx2, 38 s without, 2026-11-28), the ASan build was
# 30 of .ci/run's minutes, and the AVX2 path is the one no test machine of
# ours takes by itself. Every kernel is one template source instantiated
# per lane type, so the scalar, SSE2 and AVX-512 copies (4, 4 and 16 lanes;
# AVX-512 is this machine's own path) run the same code checked, and the
# fuzz build (clang) checks all four. The AVX2 objects share no inline code
# with the others (IsaObjectsShareNoInlineCode), so no instrumented caller
# links an uninstrumented copy. The TSan build, a fifth of the ASan build's
# time, instruments everything.
set(QUADRA_UNINSTRUMENTED_ISAS "")
if(QUADRA_SANITIZE MATCHES "address" AND NOT QUADRA_FUZZ)
  set(QUADRA_UNINSTRUMENTED_ISAS avx2)
endif()

# quadra_isa_sources(<out-var> <template.cpp.in> <kernel-name>) configures one
# copy of a kernel source per ISA and returns the generated file list.
function(quadra_isa_sources out_var template name)
  set(files)
  foreach(isa scalar sse2 avx2 avx512)
    set(QUADRA_ISA ${isa})
    set(file ${CMAKE_CURRENT_BINARY_DIR}/${name}_${isa}.cpp)
    configure_file(${template} ${file} @ONLY)
    set(options ${QUADRA_FLAGS_${isa}})
    if(isa IN_LIST QUADRA_UNINSTRUMENTED_ISAS)
      list(APPEND options -fno-sanitize=all)
    endif()
    if(options)
      set_source_files_properties(${file} PROPERTIES COMPILE_OPTIONS "${options}")
    endif()
    list(APPEND files ${file})
  endforeach()
  set(${out_var} ${files} PARENT_SCOPE)
endfunction()
