// tinygltf's implementation compiled into the fuzzer, so that its JSON and GLB parsing is
// instrumented too (coverage feedback and AddressSanitizer): Debian ships it as a prebuilt
// shared library, which the fuzzer would otherwise treat as an opaque box. The fuzzer's own
// definitions take precedence over the shared library's. Images are never decoded (the loader
// installs a no-op image callback), so stb_image is left out.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>
