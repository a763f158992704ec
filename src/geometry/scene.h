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
#include "geometry/surface_textures.h"
#include "geometry/triangle.h"
#include "core/warnings.h"

struct RTCDeviceTy;
struct RTCSceneTy;
struct RTCGeometryTy;

namespace tripath {

// A point on a surface, as a ray query returns it.
struct SurfacePoint {
    Vec3 p;
    Vec3 ng;              // geometric normal, by winding (glTF: counter-clockwise is the front)
    Vec3 ns;              // shading normal, on the same side as ng
    uint32_t triangle = 0;
    Vec2 bary;            // barycentrics of corners 1 and 2: where a textured material is read
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
    // The files it was built from (SceneDesc::sources): what identifies it.
    const std::vector<SourceFile>& sources() const { return sources_; }
    const Camera& camera() const { return camera_; }
    const Emitters& emitters() const { return emitters_; }
    // Each mesh used once and each copy of an emissive mesh in world space, then each other
    // instanced mesh once in object space: memory grows with the unique triangles, not the copies.
    const std::vector<Triangle>& triangles() const { return triangles_; }
    const std::vector<Material>& materials() const { return materials_; }
    const Material& materialOf(uint32_t triangle) const { return materials_[triangles_[triangle].material]; }
    Vec3 boundsMin() const { return lo_; }
    Vec3 boundsMax() const { return hi_; }

    // The memory the scene holds, in the parts a render's memory estimate reports
    // (integrators/memory_estimate.h).
    struct Memory {
        uint64_t triangles = 0;    // kBytesPerTriangle for each of triangles()
        uint64_t textures = 0;     // the texture images, each once however many materials read it, and
                                   // the triangles' texture coordinates and vertex colours
        uint64_t environment = 0;  // the environment map and its sampling tables
    };
    Memory memory() const;
    // What a triangle costs, all told: its Triangle (92 bytes), Embree's vertex and index buffers
    // (48), its share of the BVH and the emitters' index of it (4). Measured as the resident memory
    // a built scene adds: 187 to 209 bytes on scenes of 3600 to 1.04 million triangles (cornell
    // tessellated, BrainStem, ReciprocatingSaw, MetalRoughSpheresNoTextures), 287 on one of many
    // small meshes (2CylinderEngine's 65311 triangles).
    static constexpr uint64_t kBytesPerTriangle = 210;

    // Closest hit along origin + t·dir for t in (0, tMax).
    std::optional<SurfacePoint> intersect(Vec3 origin, Vec3 dir, float tMax = 3.0e38f) const;
    // The closest hits of up to 8 rays from one origin (a pinhole's rays through neighbouring
    // pixels), in one coherent Embree packet (faster than single rays: docs/performance-notes.md).
    // hits[i] for dirs[i].
    void intersect8(Vec3 origin, std::span<const Vec3> dirs, std::span<std::optional<SurfacePoint>> hits) const;
    // True when nothing blocks the open segment between a and b. Each end is a surface point (its
    // geometric normal given, to offset from) or a free point (a null normal: point light, sensor).
    bool unoccluded(Vec3 a, Vec3 aNormal, Vec3 b, Vec3 bNormal) const;
    // True when nothing blocks the ray from p (a surface point with geometric normal `normal`, or a
    // free point: a null normal) along unit `dir` out of the scene: toward an emitter at infinity.
    bool unoccludedToward(Vec3 p, Vec3 normal, Vec3 dir) const;

    // Shading normal at barycentrics (u, v) of a triangle, on the side of the geometric normal:
    // the interpolated normal, bent by the material's normal texture if it has one.
    Vec3 shadingNormal(uint32_t triangle, float u, float v) const;

    // The BSDF parameters of material m (a triangle's) at barycentrics b: the material itself when
    // it has no textures and the triangle no vertex colours, else its parameters there, written to
    // `scratch`: textured, and the base colour times the vertex colour (glTF's baseColorFactor ×
    // baseColorTexture × COLOR_0).
    const BsdfParams& bsdfAt(const Material& m, uint32_t triangle, Vec2 b, std::optional<BsdfParams>& scratch) const {
        if (!m.textures && !surfaceTextures_->anyColours()) return m;
        return variedBsdfAt(m, triangle, b, scratch);
    }
    // Whether bsdfAt can return anything but the material itself: some material has textures, or
    // some mesh vertex colours. Where none can, a path's vertices keep no parameters of their own
    // (paths/vertex.h: Subpath).
    bool variesBsdfs() const { return variesBsdfs_; }

    // What the alpha-mask filter of one Embree geometry reads: the scene's textures, and the index
    // of the geometry's first triangle in triangles().
    struct AlphaMask {
        const SurfaceTextures* surfaces;
        uint32_t first;
    };

private:
    // One copy of an instanced mesh: its triangles from firstTriangle on (object space), placed by
    // toWorld; Embree's instance geometry 1 + its index here.
    struct Instance {
        Affine toWorld, normalToWorld;
        uint32_t firstTriangle = 0;
        uint32_t triangleCount = 0;
    };

    void addMeshes(const SceneDesc& desc, const WarningSink& warn);
    // Appends mesh m's triangles as they are (and their texture coordinates and colours to
    // `surfaces`); returns how many were degenerate and left out.
    size_t addTriangles(const MeshDesc& m, SurfaceTextures& surfaces);
    void findBounds();
    // The texture coordinates and tangents of one triangle of mesh m, corners `corners`.
    TriangleTexCoords triangleTexCoords(const MeshDesc& m, const Triangle& t, const uint32_t corners[3]) const;
    // bsdfAt in a scene where the parameters may vary.
    const BsdfParams& variedBsdfAt(const Material& m, uint32_t triangle, Vec2 b, std::optional<BsdfParams>& scratch) const;
    // Installs the alpha-mask filter on an Embree geometry of the triangles from `first` on, if
    // any material masks.
    void setAlphaFilters(RTCGeometryTy* geom, uint32_t first);
    // Whether triangle t's material has a normal texture.
    bool hasNormalTexture(const Triangle& t) const;
    // The hit record of a ray that hit triangle `triangle` at barycentrics (u, v), parameter t.
    SurfacePoint surfacePoint(uint32_t triangle, float u, float v, float t) const;
    // The hit record of Embree's hit on primitive `primitive` of instance geometry `instance`
    // (RTC_INVALID_GEOMETRY_ID: of the world-space triangles), by the ray org + t·dir.
    SurfacePoint hitPoint(uint32_t instance, uint32_t primitive, float u, float v, Vec3 org, Vec3 dir, float t) const;
    void buildBvh();

    std::string name_;
    std::vector<SourceFile> sources_;
    std::vector<Material> materials_;
    std::vector<Triangle> triangles_;
    uint32_t worldTriangles_ = 0;     // triangles_[0, worldTriangles_) are in world space
    std::vector<Instance> instances_;
    Vec3 lo_, hi_;
    // Whether a hit rebuilt from barycentrics can land off by more than a ray origin's offset
    // (nearerHitPoint): only with coordinates beyond kMisplacingScale.
    bool mayMisplaceHits_ = false;
    CameraDesc cameraDesc_;  // the file's camera, or one framing the bounds: what reframing starts from
    Camera camera_;
    Emitters emitters_;
    std::shared_ptr<const SurfaceTextures> surfaceTextures_;  // never null; empty without textures and colours
    bool anyNormalTexture_ = false;
    bool variesBsdfs_ = false;
    std::shared_ptr<std::vector<AlphaMask>> alphaMasks_;  // what the masked geometries' filters read
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
