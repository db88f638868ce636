// Replay of untrusted recordings on the null device (CPU only): decoding, limits, round trips, regressions.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
