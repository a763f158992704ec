// The renderable scene: triangles in one Embree BVH, their materials, the emitters and the
// sensor. Built from a SceneDesc (gltf_loader or builtin_scenes), validated on the way in.
//
// A mesh with instances (scene_desc.h) is stored once: its triangles, in object space, get an
// Embree scene of their own, which each instance places in the top BVH by its transform; a hit
// on one reports world-space geometry and the triangle's index in the table, which names its
// material. An emissive mesh is placed in world space once per instance instead, as a mesh used
// once is: the emitters sample points on world-space triangles, indexed one to one.
#pragma once
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geometry/camera.h"
#include "geometry/emitters.h"
#include "geometry/scene_desc.h"
#include "geometry/triangle.h"
#include "core/warnings.h"

struct RTCDeviceTy;
struct RTCSceneTy;

namespace tripath {

// A point on a surface, as a ray query returns it.
struct SurfacePoint {
    Vec3 p;
    Vec3 ng;              // geometric normal, by winding (glTF: counter-clockwise is the front)
    Vec3 ns;              // shading normal, on the same side as ng
    uint32_t triangle = 0;
    float t = 0;          // ray parameter of the hit
};

// Moves a ray origin off the surface it leaves, to the side of `ng` that `dir` points into.
// The offset scales with the magnitude of the coordinates (Embree's hit error is relative to
// them), so it works at grazing angles and at coordinates of 1e4 and beyond.
Vec3 offsetRayOrigin(Vec3 p, Vec3 ng, Vec3 dir);

class Scene {
public:
    // Throws InputError on a scene that cannot be rendered (no emitter, bad material, …).
    Scene(SceneDesc desc, int width, int height, const WarningSink& warn = printWarning);
    // The same scene seen at another image size: its triangles, materials and emitters copied, its
    // ray-tracing BVH shared (Embree counts the references), its camera framed anew. The image size
    // is a render's parameter: one loaded scene renders at any size without building its BVH again.
    Scene(const Scene& base, int width, int height);
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    const std::string& name() const { return name_; }
    const Camera& camera() const { return camera_; }
    const Emitters& emitters() const { return emitters_; }
    // Each mesh used once and each copy of an emissive mesh in world space, then each other
    // instanced mesh once in object space: memory grows with the unique triangles, not the copies.
    const std::vector<Triangle>& triangles() const { return triangles_; }
    const std::vector<Material>& materials() const { return materials_; }
    const Material& materialOf(uint32_t triangle) const { return materials_[triangles_[triangle].material]; }
    Vec3 boundsMin() const { return lo_; }
    Vec3 boundsMax() const { return hi_; }

    // Closest hit along origin + t·dir for t in (0, tMax).
    std::optional<SurfacePoint> intersect(Vec3 origin, Vec3 dir, float tMax = 3.0e38f) const;
    // The closest hits of up to 8 rays from one origin (a pinhole's rays through neighbouring
    // pixels), in one coherent Embree packet: bench/README.md measured 4× the rays/s of single rays
    // for a pass's camera rays on cornell. hits[i] for dirs[i].
    void intersect8(Vec3 origin, std::span<const Vec3> dirs, std::span<std::optional<SurfacePoint>> hits) const;
    // True when nothing blocks the open segment between a and b. Each end is a surface point (its
    // geometric normal given, to offset from) or a free point (a null normal: point light, sensor).
    bool unoccluded(Vec3 a, Vec3 aNormal, Vec3 b, Vec3 bNormal) const;
    // True when nothing blocks the ray from p (a surface point with geometric normal `normal`, or a
    // free point: a null normal) along unit `dir` out of the scene: toward an emitter at infinity.
    bool unoccludedToward(Vec3 p, Vec3 normal, Vec3 dir) const;

    // Shading normal at barycentrics (u, v) of a triangle, on the side of the geometric normal.
    Vec3 shadingNormal(uint32_t triangle, float u, float v) const;

private:
    // One copy of an instanced mesh: its triangles from firstTriangle on (object space), placed by
    // toWorld; Embree's instance geometry 1 + its index here.
    struct Instance {
        Affine toWorld, normalToWorld;
        uint32_t firstTriangle = 0;
        uint32_t triangleCount = 0;
    };

    void addMeshes(const SceneDesc& desc, const WarningSink& warn);
    size_t addTriangles(const MeshDesc& m);
    void findBounds();
    // The hit record of a ray that hit triangle `triangle` at barycentrics (u, v), parameter t.
    SurfacePoint surfacePoint(uint32_t triangle, float u, float v, float t) const;
    // The hit record of Embree's hit on primitive `primitive` of instance geometry `instance`
    // (RTC_INVALID_GEOMETRY_ID: of the world-space triangles).
    SurfacePoint hitPoint(uint32_t instance, uint32_t primitive, float u, float v, float t) const;
    void buildBvh();

    std::string name_;
    std::vector<Material> materials_;
    std::vector<Triangle> triangles_;
    uint32_t worldTriangles_ = 0;     // triangles_[0, worldTriangles_) are in world space
    std::vector<Instance> instances_;
    Vec3 lo_, hi_;
    CameraDesc cameraDesc_;  // the file's camera, or one framing the bounds: what reframing starts from
    Camera camera_;
    Emitters emitters_;
    RTCDeviceTy* device_ = nullptr;
    RTCSceneTy* rtcScene_ = nullptr;
};

// A camera looking at the whole box [lo, hi] from +z, used when the scene has none.
CameraDesc frameBounds(Vec3 lo, Vec3 hi);

// The width of one pixel on the surfaces the camera sees: for a 16×16 grid of pixel centres, the
// distance to the first surface that scatters through no delta lobe (through mirrors and glass,
// unfolded) times the angle between neighbouring pixels' rays, and the median of those; 0 if no
// ray reaches such a surface. A scale for image-space quantities (the merge radius) that
// follows the resolution and what the camera looks at, not the extent of the whole scene.
float medianPixelFootprint(const Scene& scene);

}  // namespace tripath
