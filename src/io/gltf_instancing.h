// EXT_mesh_gpu_instancing: a node that carries it draws its mesh once per instance, at the node's
// world transform × the instance's T × R × S (from the TRANSLATION, ROTATION and SCALE accessors;
// an absent one takes glTF's default), and not at the node's transform alone. Read here with
// every count, value and scale checked. A header of the io library's own (the loader's interface
// is gltf_loader.h).
#pragma once
#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include <optional>
#include <vector>

#include "geometry/scene_desc.h"
#include "io/gltf_accessors.h"
#include "io/gltf_checks.h"

namespace tripath::gltf {

inline constexpr const char* kInstancingExtension = "EXT_mesh_gpu_instancing";

// The instances of node `index`, or none when it has no EXT_mesh_gpu_instancing. Fails, one
// line, on a malformed extension, non-float accessors, counts that disagree, a non-finite value,
// a zero-length rotation or a scale that collapses space.
std::optional<std::vector<TrsDesc>> readInstances(const tinygltf::Node& node, int index, const Accessors& accessors,
                                                  const Report& report);

// An instance's own transform: T × R × S, the rotation normalised.
glm::dmat4 instanceMatrix(const TrsDesc& trs);

}  // namespace tripath::gltf
