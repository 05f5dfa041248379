# How ctest schedules the discovered tests (included by CTestTestfile.cmake after the suites'
# test lists). `make test` runs ctest with one job per core, so:
# - the longest tests get a COST (their seconds in a clean-clone run on 2 cores) and start first,
#   instead of leaving one core idle at the end of the run (the tests that time a command
#   against a deadline leave it seconds of slack, and run beside others);
# - the tests that check Tellus through other programs' clients (the Ecosystem suite: CesiumJS in
#   headless Chromium, the Khronos validators, the installed package) and the demo test (the job
#   `make demo` runs) are labelled `long`: `make test` leaves them to `make test-long`;
# - the Ecosystem tests run one at a time: most drive headless Chromium with software WebGL on
#   every core against a page timeout, and they share the Korea store and the npm folder.
# A name not (or no longer) discovered is skipped.
cmake_policy(PUSH)
cmake_policy(SET CMP0057 NEW)  # if(IN_LIST): ctest reads this file without the project's policies
set(_tellus_discovered ${tellus_cache_tests_TESTS} ${tellus_unit_tests_TESTS} ${tellus_gpu_tests_TESTS}
    ${tellus_cli_tests_TESTS})

set(_tellus_long_tests
    Ecosystem.Tiles3dSetIsValidWithinItsErrorsAndWholeInCesium 160
    Hostile.EveryNumericOptionRefusesNonFiniteAndOutOfRangeValues 86
    Cli.DemoComparesTheRenderersAndWritesThePages 71
    Ecosystem.QuantizedMeshOfKoreaRendersInCesium 69
    Ecosystem.QuantizedMeshGlobeIsRoundAndWholeInCesium 68
    StacksCli.QuadRenderAndBench 43
    Ecosystem.QuantizedMeshMeetsTheBackgroundReliefAtTheDataEdge 38
    StacksLodRendererTest.AmortisedUpdatesFromASmallPoolLeaveNoHole 36
    MpiBuildCli.AnyNumberOfRanksWritesTheSameBytes 33
    HostileSurfaces.AKilledExportLeavesACompleteTileSet 32
    ImageryCli.GlobeRenderersDrapeImageryByLatitudeAndLongitude 31
    Ecosystem.QuantizedMeshIsWithinItsErrorIn3DByAnIndependentDecoder 30
    BenchCli.CodecsRunsTheChosenRowsWithTheFractalRangeOptions 29
    Cli.RendersTheKoreaMosaicObliquelyWithLandAndSea 25
    Ecosystem.GltfExportsPassTheKhronosValidator 25
    StacksLodRendererTest.AnEditRemakesEveryAffectedNodeAtOnceWithoutCracks 25
    Ecosystem.QuantizedMeshCarriesTheWaterMask 23
    HostileSurfaces.OutputFoldersNeverReplaceWhatTellusDidNotWrite 22
    StacksLodRendererTest.GeomorphingSpreadsASwitchOverFramesWithoutCracks 21
    BenchCli.RenderersDoNotWaitForTheGpuInTheirFrames 21
    BenchCli.FractalStoreAndBaseIncremental 21
    GlobeCli.GlobalStoreBuildInfoVerifyExportRender 21)
while(_tellus_long_tests)
  list(POP_FRONT _tellus_long_tests _name _seconds)
  if(_name IN_LIST _tellus_discovered)
    set_tests_properties(${_name} PROPERTIES COST ${_seconds})
  endif()
endwhile()

foreach(_name IN LISTS _tellus_discovered)
  if(_name MATCHES "^Ecosystem\\.")
    set_tests_properties(${_name} PROPERTIES RESOURCE_LOCK ecosystem LABELS "cli;long")
  elseif(_name STREQUAL "Cli.DemoComparesTheRenderersAndWritesThePages")
    set_tests_properties(${_name} PROPERTIES LABELS "cli;long")
  endif()
endforeach()
cmake_policy(POP)
