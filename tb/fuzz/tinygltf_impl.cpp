// tb/fuzz/tinygltf_impl.cpp - tinygltf compiled into the fuzzer (instrumented), instead of Debian's
// prebuilt libtinygltf.so. Images are never decoded by the loader (it installs its own no-op image
// loader), so stb_image is left out: scripts/fuzz.sh defines TINYGLTF_NO_STB_IMAGE(_WRITE) and
// TINYGLTF_NO_EXTERNAL_IMAGE for every file, so that the TinyGLTF class is the same everywhere.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
