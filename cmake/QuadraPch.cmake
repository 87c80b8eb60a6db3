# Precompiled headers (issue 45: a first image in minutes). Half of a typical
# translation unit's compile is parsing the standard library and GLM (128k
# preprocessed lines for api/renderer.cpp, 7 of its 13 CPU-seconds), so each
# target parses them once. The per-ISA kernel copies skip it
# (quadra_isa_sources): their ISA flags differ from the header's.
# Sanitizer and fuzz builds compile without it, so a source that forgets an
# include the header happens to provide still fails to build somewhere.
# Headers read from a PCH lose their system-header status in GCC 12, so its
# false -Warray-bounds alarms inside std::string (char_traits.h) surface as
# errors where the inliner meets them: three test files did, so the test
# program, which no first run builds, compiles without it.
option(QUADRA_PCH "Precompile the standard and GLM headers each target parses" ON)
set(QUADRA_PCH_HEADERS <algorithm> <array> <cmath> <cstdint> <cstdio> <cstring> <filesystem>
    <functional> <limits> <map> <memory> <optional> <sstream> <string> <utility> <vector>
    <glm/glm.hpp>)

# quadra_precompile_headers(<target> [more headers...])
function(quadra_precompile_headers target)
  if(QUADRA_PCH AND NOT QUADRA_SANITIZE AND NOT QUADRA_FUZZ)
    target_precompile_headers(${target} PRIVATE ${QUADRA_PCH_HEADERS} ${ARGN})
  endif()
endfunction()
