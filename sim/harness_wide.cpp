// The harness of the wide bit engine's build (BitEngine=1, `make harness-wide`): the
// same harness, told which build it drives so that it accepts a wide image's extension
// words. A file of its own, so that its object never stands in for the scalar one's
// (Verilator puts a user source's object beside the build directory, not in it).
#define BB_BIT_ENGINE 1
#include "harness.cpp"
