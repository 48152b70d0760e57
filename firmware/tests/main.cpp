// The firmware test image's entry point: runs every TT_TEST linked into the image
// (one file per area: rotor_tests.cpp, ...) and prints "N passed, N failed".
#define TT_MAIN
#include "tinytest.hpp"
