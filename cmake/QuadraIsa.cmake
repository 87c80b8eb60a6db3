# Per-ISA kernel translation units: the ISA flags go on those files only, so the
# rest of the build (and the shipped binary's baseline) stays plain x86-64/SSE2.
set(QUADRA_FLAGS_sse2 "-msse2")
set(QUADRA_FLAGS_avx2 "-mavx2;-mf16c")
# GCC 12's own avx512fintrin.h trips -W(maybe-)uninitialized (its _mm512_undefined_*
# idiom), a known false positive; silenced for this file only.
set(QUADRA_FLAGS_avx512
    "-mavx512f;-mavx512bw;-mavx512dq;-mavx512vl;-mavx2;-mf16c;-Wno-maybe-uninitialized;-Wno-uninitialized")

# Sanitizer builds leave some wide-lane copies of the kernels uninstrumented:
# GCC takes 7-9 CPU-minutes for each instrumented tile kernel (542 s user
# for tile_kernel_avx2 under ASan+UBSan, 2026-11-28), which put .ci/run past
# CI's 90 minutes. Every kernel is one template source instantiated per lane
# type, so the copies that stay instrumented run the same code. Under TSan
# the AVX2 and AVX-512 copies go uninstrumented: a kernel works on one
# tile's private buffers, and the threads that hand out tiles and share
# frames are the stage code's, instrumented, while the scalar and SSE2
# kernels run under TSan in Determinism.* (these ISA objects share no inline
# code with the others, IsaObjectsShareNoInlineCode, so no instrumented
# caller links an uninstrumented copy). Under ASan+UBSan the AVX2 copy does:
# scalar, SSE2 and AVX-512 (4, 4 and 16 lanes, this machine's own path) stay
# checked, and the fuzz build (clang) checks all four.
set(QUADRA_UNINSTRUMENTED_ISAS "")
if(QUADRA_SANITIZE MATCHES "thread")
  set(QUADRA_UNINSTRUMENTED_ISAS avx2 avx512)
elseif(QUADRA_SANITIZE AND NOT QUADRA_FUZZ)
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
