# The fuzz targets in the normal build (any compiler, no sanitizers, no libFuzzer): each
# fuzz/<target>.cpp with fuzz/replay_main.cpp as replay_<target>, and a test that feeds it the
# kept crashers (fuzz/regressions) and the hand-made seeds (fuzz/seeds) once. The fuzzers' own
# invariant checks abort, so a broken invariant fails the test; a change to an API the fuzzers use
# fails the build here rather than in the clang build of fuzz/run.sh.
set(lucerna_replay_targets fuzz_scene fuzz_ply fuzz_gzip fuzz_build fuzz_checkpoint)
set(replay_fuzz_scene_libs lucerna_scene)
set(replay_fuzz_ply_libs lucerna_scene)
set(replay_fuzz_gzip_libs lucerna_scene)
set(replay_fuzz_build_libs lucerna_scene)
set(replay_fuzz_checkpoint_libs lucerna_render)
foreach(target ${lucerna_replay_targets})
  add_executable(replay_${target} ${CMAKE_SOURCE_DIR}/fuzz/${target}.cpp ${CMAKE_SOURCE_DIR}/fuzz/replay_main.cpp)
  target_link_libraries(replay_${target} PRIVATE ${replay_${target}_libs})
  set_target_properties(replay_${target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz-replay)
  add_test(NAME ${target}.replays_regressions_and_seeds
           COMMAND replay_${target} ${CMAKE_SOURCE_DIR}/fuzz/regressions ${CMAKE_SOURCE_DIR}/fuzz/seeds)
  set_tests_properties(${target}.replays_regressions_and_seeds PROPERTIES LABELS fuzz-replay TIMEOUT 300)
endforeach()
