// The glTF document as the loader checks it before tinygltf reads it: the JSON text (in a binary
// glTF, after the container's header), the parsed JSON and its asset.version. tinygltf would say
// only "Invalid magic." of a renamed file, pass nlohmann's exception text on as it is, call a .gltf
// of `{}` unreadable and load a version "3.0" without a word; these checks name what is wrong in
// one line, quoting none of the file. A header of the io library's own (the loader's
// interface is gltf_loader.h).
#pragma once
#include <nlohmann/json.hpp>

#include <string_view>
#include <vector>

#include "io/gltf_checks.h"

namespace tripath::gltf {

// The JSON in the file's bytes: all of them, or for a binary glTF (GLB) its first chunk, once the
// header is checked: the magic "glTF", container version 2, the lengths within the file and a
// first chunk of type JSON.
std::string_view jsonText(const std::vector<char>& bytes, bool binary, const Report& report);

// `text` parsed; fails with "not valid JSON at line L, column C (what nlohmann found)".
nlohmann::json parseJson(std::string_view text, const Report& report);

// Fails unless `doc` is an object with an "asset" object whose "version" is "2.<minor>".
void checkAsset(const nlohmann::json& doc, const Report& report);

}  // namespace tripath::gltf
