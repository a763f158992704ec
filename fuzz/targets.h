// The fuzz targets' entry points, by name. Each fuzz/<name>_fuzzer.cpp defines one and, built as a
// libFuzzer executable (-DTRIPATH_FUZZ=ON: TRIPATH_LIBFUZZER), hands it LLVMFuzzerTestOneInput's
// inputs; the test suite compiles the same files without libFuzzer and calls them by these names
// (tests/test_fuzz_inputs.cpp), so both targets fit in one executable.
//
// The contract under test (docs/design.md §5): any input ends normally (read and used, or refused
// with an InputError, which the entry point catches and returns the message of; "" when the input
// was used); anything else (another exception, a crash, a hang, a leak) is a finding.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace tripath::fuzz {

// fuzz/gltf_fuzzer.cpp: the input as a .gltf or .glb file, loaded, built into a Scene and sampled.
std::string loadAndSampleGltf(const uint8_t* data, size_t size);

// fuzz/environment_checkpoint_fuzzer.cpp: the input's first byte chooses, the rest is the file: an
// environment map (read and sampled) or a checkpoint (read and resumed for a pass).
std::string readEnvironmentOrCheckpoint(const uint8_t* data, size_t size);

}  // namespace tripath::fuzz
