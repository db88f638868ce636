# Record decoding + replay onto the null device under the validation wrapper (seeds in seeds/replay_fuzzer/;
# the inputs it found are regression tests in tests/replay/regressions/).
bricklight_add_fuzzer(replay_fuzzer SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/replay_fuzzer.cpp LIBS bricklight_rhi)
