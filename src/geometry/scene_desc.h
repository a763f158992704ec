// A scene as plain data, before any acceleration structure exists: what the glTF loader and the
// built-in scenes produce and what Scene (geometry/scene.h) is built from. World space throughout,
// but for the meshes that instances place: each is kept once, in its own space, with the transforms
// that place its copies, so that a model of many copies costs the memory of one.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/affine.h"
#include "geometry/material.h"
#include "core/vec.h"

namespace tripath {

struct MeshDesc {
    std::string name;
    std::vector<Vec3> positions;       // world space
    std::vector<Vec3> normals;         // world space shading normals; empty or one per position
    std::vector<uint32_t> indices;     // three per triangle
    int material = 0;                  // index into SceneDesc::materials
    std::vector<Vec2> texCoords[2]{};  // TEXCOORD_0 and _1: empty or one per position
    std::vector<Vec3> tangents{};      // world space TANGENT xyz: empty or one per position
    std::vector<float> tangentSigns{}; // TANGENT w (±1, the bitangent's sign), one per tangent
    // COLOR_0: linear RGBA in [0, 1], empty or one per position. RGB multiplies the base colour
    // (BsdfParams::albedo) and A its alpha, interpolated over each triangle.
    std::vector<std::array<float, 4>> colours{};
};

// A KHR_lights_punctual light. Point and spot: radiant intensity I = colour × intensity (W/sr),
// a spot's falling off as t² between its inner and outer cone; directional: irradiance
// E = colour × intensity (W/m²) on a surface facing it. Spot and directional lights shine along
// `direction`, their node's −Z.
struct LightDesc {
    enum class Kind { Point, Spot, Directional };
    Vec3 position;
    Spectrum intensity;
    Kind kind = Kind::Point;
    Vec3 direction{0, 0, -1};     // unit
    float innerConeAngle = 0;     // radians, spot
    float outerConeAngle = kPi / 4;
};

// A file a scene was built from, known by the FNV-1a hash (core/fnv1a.h) of the bytes read from
// it: what checkpoints and references record of their scene (requests/scene_identity.h), so that
// the same content is the same scene whatever path named it, and an edited file is not.
struct SourceFile {
    std::string name;  // for messages: the file's name as the scene or the command line gave it
    uint64_t hash = 0;
};

// Radiance from infinitely far away, as an equirectangular map (geometry/environment.h gives the
// convention): width × height linear RGB radiances, rows from the top. None when empty.
struct EnvironmentDesc {
    int width = 0, height = 0;
    std::vector<Spectrum> texels;
    std::string source;           // the file, or the constant as given, for messages and metadata
    uint64_t hash = 0;            // of the texels as read, before any scale: the content of `source`
    bool present() const { return !texels.empty(); }
};

// A transform as EXT_mesh_gpu_instancing gives one: translation × rotation × scale.
struct TrsDesc {
    Vec3 translation{0, 0, 0};
    float rotation[4] = {0, 0, 0, 1};  // quaternion x, y, z, w
    Vec3 scale{1, 1, 1};
    bool operator==(const TrsDesc&) const = default;
};

// Copies of one mesh: SceneDesc::meshes[mesh], in object space, appears once per transform
// (object to world; normals go through its inverse transpose), and not as it is. A mesh may have
// several such groups (one per glTF node that places it, say).
struct InstancesDesc {
    int mesh = 0;
    std::vector<Affine> toWorld;
    // When EXT_mesh_gpu_instancing gave the group: toWorld[i] is parent × trs[i] (as the loader
    // composes them), kept so that an export says them as compactly. Empty otherwise.
    std::vector<TrsDesc> trs;
    Affine parent;
};

struct CameraDesc {
    bool present = false;          // false: frame the scene's bounds from a default direction
    Vec3 position{0, 0, 0};
    Vec3 forward{0, 0, -1};        // unit view direction
    Vec3 up{0, 1, 0};              // unit up direction, orthogonal to forward
    float yfov = 0.6911f;          // vertical field of view, radians
};

struct SceneDesc {
    std::string name;              // file path or built-in name, for messages and metadata
    std::vector<SourceFile> sources;  // what it was built from, in the order read (a built-in: its name)
    std::vector<Material> materials;
    std::vector<MeshDesc> meshes;
    std::vector<InstancesDesc> instances;
    std::vector<LightDesc> lights;
    EnvironmentDesc environment;
    CameraDesc camera;
};

}  // namespace tripath
