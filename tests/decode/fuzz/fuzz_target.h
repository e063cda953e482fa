#pragma once

#include <cstddef>
#include <cstdint>

// The libFuzzer entry point each fuzz target defines. Under clang with -DLFSP_FUZZ=ON it is linked with
// -fsanitize=fuzzer; otherwise replay_main.cc drives it over a corpus (a CTest test).
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
