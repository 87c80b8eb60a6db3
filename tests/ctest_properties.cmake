# ctest properties of discovered GoogleTest cases, set by name (a test that
# is renamed or gone is ignored by ctest): the order the longest start in,
# and which pure-arithmetic checks only the Release suite runs.

# A fresh clone (CI) has no timings of its own (Testing/Temporary/
# CTestCostData.txt), so ctest would start tests in declaration order, and a
# long one that starts last runs alone on one core at the end of the suite;
# a higher COST starts first. Costs are seconds under ASan on the 2-core
# machine: the stability report's 141 s was CI's measurement (2026-11-25), shared
# among its parts by their Release times (random triangles per sample ~75%);
# the screen-grid instances share the 60 s the one screen-grid test took
# then as their Release run times do (random-triangles ~half, subpixel-plane
# ~40%, the other 16 instances the rest).
set_tests_properties([=[Cli/StabilityReport.PassesEveryCheck/samples_random_triangles]=]
                     PROPERTIES COST 110)
set_tests_properties([=[Cli/StabilityReport.PassesEveryCheck/random_triangles]=] PROPERTIES COST 30)
set_tests_properties([=[Cli/StabilityReport.PassesEveryCheck/perspective]=] PROPERTIES COST 25)
set_tests_properties([=[ReferenceTracer/ScreenGrid.FindsTheHitsTheExhaustiveSearchFinds/random_triangles]=]
                     PROPERTIES COST 30)
set_tests_properties([=[ReferenceTracer/ScreenGrid.FindsTheHitsTheExhaustiveSearchFinds/subpixel_plane]=]
                     PROPERTIES COST 24)

# heavy_arithmetic: double-precision lab code only (no engine), whose code
# paths, the tracer's parallel rows included, lighter instances of the same
# test run too. .ci/run leaves them out of the sanitizer suites (ctest -LE
# heavy_arithmetic); the Release suite runs them. What they add is the
# exhaustive search over 20000 and 80000 triangles, not a path the other 15
# screen-grid scenes miss.
set_tests_properties([=[ReferenceTracer/ScreenGrid.FindsTheHitsTheExhaustiveSearchFinds/random_triangles]=]
                     [=[ReferenceTracer/ScreenGrid.FindsTheHitsTheExhaustiveSearchFinds/subpixel_plane]=]
                     PROPERTIES LABELS heavy_arithmetic)

# The soak tests (tests/test_soak.cpp): 1,000 frames each in Release (2.7 s
# and 0.8 s on 2 threads), 150 under a sanitizer.
set_tests_properties([=[Soak.ThousandFramesOfTexturesAndBlendingKeepResidentMemoryFlat]=]
                     PROPERTIES COST 20)
set_tests_properties([=[Soak.ThousandFramesOfAnAnimatedSequenceKeepResidentMemoryFlat]=]
                     PROPERTIES COST 6)

# tsan_repeat: the stability report's random-triangle sections, the longest
# tests under ThreadSanitizer (~280 s of the 2-core machine, issue 4's
# measurement). Their renders on 2 threads run the code the report's first
# section (its determinism check on 1, 2, 3 and 8 threads) and
# Determinism.* run under TSan, on more triangles: .ci/run leaves them out of
# the TSan suite only (ctest -LE tsan_repeat); the Release and ASan suites
# run them.
set_tests_properties([=[Cli/StabilityReport.PassesEveryCheck/samples_random_triangles]=]
                     [=[Cli/StabilityReport.PassesEveryCheck/random_triangles]=]
                     PROPERTIES LABELS tsan_repeat)

# The area reference on builtin:checker-plane (a pixel column costs the ~1.2e5
# texel rows it crosses: 12 s in Release on 2 threads) and on the huge-
# coordinate scenes (9 s, most of it their 16x16 rays): double-precision lab
# code whose paths the floor, coverage and overlap cases of
# tests/test_reference_area.cpp run in milliseconds, so only the Release
# suite runs them.
set_tests_properties([=[ReferenceArea.CheckerPlaneConvergesAndMatchesDenseRaysWhereThoseConverge]=]
                     PROPERTIES COST 12 LABELS heavy_arithmetic)
set_tests_properties([=[ReferenceArea.HugeCoordinatesTakeTheRaysWhereTheyCannotBeClipped]=]
                     PROPERTIES COST 9 LABELS heavy_arithmetic)

# The lit reports' end-to-end tests (tests/test_report_lighting.cpp,
# tests/test_report_frames.cpp): about twenty quadra and quadra-llvmpipe
# processes each (24 s and 15 s a run in Release on 2 threads), so they start
# first. Their renders' threaded code is what the lit frame tests run under
# TSan in-process, so the TSan suite leaves them out (tsan_repeat); the Release
# and ASan suites run them.
set_tests_properties([=[ReportLighting.ScoresQuadrasLitFramesAgainstTheIdealAndTimesThem]=]
                     PROPERTIES COST 60 LABELS tsan_repeat)
set_tests_properties([=[ReportFrames.TakesTheLitShadingToBothRenderers]=]
                     PROPERTIES COST 30 LABELS tsan_repeat)
