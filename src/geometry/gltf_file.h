// Reading a glTF file into tinygltf's model, within the rules for the files it may open: the
// scene file is .glb or .gltf by its magic bytes (or the .glb extension); every external buffer
// URI is checked (external_files.h) before tinygltf opens any file, so that a refusal names the
// buffer, and tinygltf's file-system callbacks then open only the approved buffer files; image
// files are never opened or decoded. A header of the geometry library's own (the loader's
// interface is gltf_loader.h).
#pragma once
#include <tiny_gltf.h>

#include "geometry/gltf_checks.h"

namespace tripath::gltf {

// The model in the file report.path() names; fails with tinygltf's message, made one line, when it
// does not parse. Passes tinygltf's warnings on, minus those about images (textures are ignored).
// allowExternalFiles: GltfOptions::allowExternalFiles.
tinygltf::Model readModel(bool allowExternalFiles, Report& report);

}  // namespace tripath::gltf
