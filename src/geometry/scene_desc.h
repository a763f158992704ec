// A scene as plain data, before any acceleration structure exists: what the glTF loader and the
// built-in scenes produce and what Scene (geometry/scene.h) is built from. World space throughout.
#pragma once
#include <string>
#include <vector>

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
};

// KHR_lights_punctual point light: radiant intensity I = colour × intensity (W/sr).
struct PointLightDesc {
    Vec3 position;
    Spectrum intensity;
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
    std::vector<Material> materials;
    std::vector<MeshDesc> meshes;
    std::vector<PointLightDesc> pointLights;
    CameraDesc camera;
};

}  // namespace tripath
