// Catch2's implementation and main(), compiled once for every test program that has no main of its own (it
// is the slowest file to compile in each): programs link bricklight_catch_main and hold only their tests.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
