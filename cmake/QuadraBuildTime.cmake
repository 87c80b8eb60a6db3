# What makes the build shorter without changing a bit of the code it builds
# (issue 45: a first image in minutes; docs/performance.md "Build time and the
# first run").
#
# Precompiled headers: half of a typical translation unit's compile was
# parsing the standard library and GLM (128k preprocessed lines for
# api/renderer.cpp, 7 of its 13 CPU-seconds), so each target parses them once.
# Unity batches: the small files of the engine, the lab, the CLI library and
# the programs compiled eight to a translation unit, which parses their own
# headers once a batch and halves those files' compile; so file-local names
# (anonymous-namespace helpers, constants) must differ between the files of
# one target. The per-ISA kernel copies take part in neither
# (quadra_isa_sources): their ISA flags differ from the header's, and each is
# a large file of its own.
#
# Sanitizer and fuzz builds compile every file on its own without either, so
# a source that forgets an include a batch or the header happens to provide
# still fails to build somewhere. Headers read from a PCH lose their
# system-header status in GCC 12, so its false -Warray-bounds alarms inside
# std::string (char_traits.h) surface as errors where the inliner meets them:
# three test files did, so the test program, which no first run builds,
# compiles without it.
option(QUADRA_FAST_BUILD "Precompiled headers and unity batches for the engine, lab and CLI" ON)
set(QUADRA_PCH_HEADERS <algorithm> <array> <cmath> <cstdint> <cstdio> <cstring> <filesystem>
    <functional> <limits> <map> <memory> <optional> <sstream> <string> <utility> <vector>
    <glm/glm.hpp>)

# quadra_build_fast(<target>): the engine's header serves the other static
# libraries, which compile with the same flags; an executable (-fPIE, not
# -fPIC) needs its own.
function(quadra_build_fast target)
  if(QUADRA_FAST_BUILD AND NOT QUADRA_SANITIZE AND NOT QUADRA_FUZZ)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "STATIC_LIBRARY" AND NOT target STREQUAL "quadra_engine")
      target_precompile_headers(${target} REUSE_FROM quadra_engine)
    else()
      target_precompile_headers(${target} PRIVATE ${QUADRA_PCH_HEADERS})
    endif()
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  endif()
endfunction()
