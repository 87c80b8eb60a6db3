# quadra_fuzz_targets: the fuzz targets' code without libFuzzer, for the fuzz
# build (CMakeLists.txt here) and for the test suite, which replays the seed
# corpus and every kept finding through it (tests/test_fuzz_corpus.cpp).
set(QUADRA_FUZZ_DIR ${CMAKE_CURRENT_LIST_DIR})
add_library(quadra_fuzz_targets STATIC ${QUADRA_FUZZ_DIR}/fuzz_gltf.cpp
            ${QUADRA_FUZZ_DIR}/fuzz_image.cpp ${QUADRA_FUZZ_DIR}/fuzz_environment.cpp
            ${QUADRA_FUZZ_DIR}/fuzz_lookups_csv.cpp
            ${QUADRA_FUZZ_DIR}/fuzz_render.cpp)
target_include_directories(quadra_fuzz_targets PUBLIC ${QUADRA_FUZZ_DIR}
                           PRIVATE ${PROJECT_SOURCE_DIR}/tools)
target_link_libraries(quadra_fuzz_targets PUBLIC quadra_engine PRIVATE quadra_warnings TBB::tbb)
# The lookups CSV reader: the CLI library's where it is built; the fuzz build
# has no CLI, so it compiles the reader's one file itself.
if(TARGET quadra_cli)
  target_link_libraries(quadra_fuzz_targets PUBLIC quadra_cli)
else()
  target_sources(quadra_fuzz_targets PRIVATE ${PROJECT_SOURCE_DIR}/tools/lookups_csv.cpp)
endif()
