// libFuzzer target for the native solver; what one input does and what is checked: fuzz_harness.h.
// Build and run: scripts/run_fuzz.sh [SECONDS].
#include <cstddef>
#include <cstdint>

#include "fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  gauss_fuzz::run_one(data, size);
  return 0;
}
