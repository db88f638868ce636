// The conformance kit's cases as Catch2 tests: an option next to the plain runner (conformance::runAll) for a
// program that already uses Catch2 (library bricklight_conformance_catch2, built with BRICKLIGHT_TESTS=ON;
// catch_registration.cpp uses only the kit's public API, so it can also be compiled into your own tests).
#pragma once

#include <vector>

#include "bricklight/conformance.h"

namespace bricklight::conformance {

// Registers one Catch2 test per (backend, case), named "<backend>/<case>" and tagged
// [conformance][<backend name>], and when there are two or more backends one test per case named
// "cross/<case>" and tagged [conformance][cross] that compares the first two backends' outputs. Call it
// before running the Catch2 session.
void registerCatchTests(const std::vector<Backend>& backends);

}  // namespace bricklight::conformance
