#pragma once
// The entry point every fuzz target defines (libFuzzer's): one input, any
// bytes. A target returns 0 for every input the program answers as it should
// (a valid case, or perimorph::Error: a message a user can act on); anything
// else — another exception, an assertion, a sanitizer report, a crash — is a
// finding. Built with libFuzzer under clang (-DPERIMORPH_FUZZ=ON), or with
// replay_main.cpp, which runs a corpus through it (CTest, any compiler).

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
