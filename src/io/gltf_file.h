// Reading a glTF file into tinygltf's model, within the rules for the files it may open: the scene
// file is .glb or .gltf by its magic bytes (or the .glb extension); its container, JSON, nesting
// and version are checked first (gltf_document.h); every buffer URI is checked before tinygltf
// opens any file, so that a refusal names the buffer (a data: URI's size, a URI scheme, the file it
// names: external_files.h), and tinygltf's file-system callbacks then open only the approved buffer
// files; image files are left to gltf_textures.h, which reads them under the same rules. A header
// of the io library's own (the loader's interface is gltf_loader.h).
#pragma once
#include <tiny_gltf.h>

#include <filesystem>
#include <vector>

#include "geometry/scene_desc.h"
#include "io/gltf_checks.h"

namespace tripath::gltf {

// The model in the file report.path() names; fails with one line saying what is wrong, quoting at
// most excerpts of the file (tinygltf's own message, shortened, for what only tinygltf checks).
// Passes tinygltf's warnings on, shortened, minus those about images (gltf_textures.h reads them).
// allowExternalFiles: GltfOptions::allowExternalFiles. Appends the files it reads to `sources`, each
// hashed from the bytes the model was made from: the scene file by its name, then the buffer files
// by their decoded URIs.
tinygltf::Model readModel(bool allowExternalFiles, Report& report, std::vector<SourceFile>& sources);

// The folder of the scene file report.path() names, absolute with symlinks resolved: what the
// files a scene names are resolved against (external_files.h).
std::filesystem::path sceneFolder(const Report& report);

}  // namespace tripath::gltf
