#include "geometry/scene.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <set>
#include <stdexcept>
#include <utility>

#include "geometry/embree_isa.h"
#include "core/error.h"
#include "core/stats.h"

namespace tripath {

namespace {
constexpr Counter kClosestHitRays{Event::ClosestHitRays};
constexpr Counter kShadowRays{Event::ShadowRays};
constexpr Counter kBsdfDerivations{Event::BsdfDerivations};
}  // namespace

// The coordinates below which no hit rebuilt from barycentrics lands off by more than a ray
// origin's absolute offset: its error, about 2^-23 of the triangle's coordinates, stays under
// 2^-16 (offsetRayOrigin) below 2^7.
constexpr float kMisplacingScale = 128;

// A hit point computed from barycentrics is off the triangle's plane by a few ulps of the LARGEST
// coordinate involved (not of the coordinate along the normal, which may be near zero), so the
// offset is relative to max|p|: 2^-18 ≈ 32 ulps of it, plus 2^-16 absolute for scenes near the
// origin. At unit scale that is 1.5e-5 m; at coordinates of 1e4, 0.04 m — the float grid there is
// 1e-3 m, so nothing finer can be trusted anyway (test_scene checks grazing rays at both scales).
Vec3 offsetRayOrigin(Vec3 p, Vec3 ng, Vec3 dir) {
    const float scale = maxComponent(abs(p)) * 0x1p-18f + 0x1p-16f;
    return p + (dot(ng, dir) < 0 ? -ng : ng) * scale;
}

CameraDesc frameBounds(Vec3 lo, Vec3 hi) {
    CameraDesc c;
    const Vec3 centre = (lo + hi) * 0.5f;
    const float radius = 0.5f * length(hi - lo);
    c.yfov = 0.6911f;  // 39.6°, a 35 mm lens's vertical field
    c.position = centre + Vec3(0, 0, radius / std::sin(0.5f * c.yfov) * 1.05f);
    c.forward = Vec3(0, 0, -1);
    c.up = Vec3(0, 1, 0);
    c.present = true;
    return c;
}

namespace {

// Beyond 1e15 m, squared distances between vertices (r² in g and every area pdf) come close to
// float's range; nothing physical needs such coordinates.
bool isCoordinate(Vec3 p) {
    constexpr float kMaxCoordinate = 1e15f;
    return isFinite(p) && maxComponent(abs(p)) <= kMaxCoordinate;
}

void checkMesh(const SceneDesc& desc, const MeshDesc& m) {
    if (m.indices.size() % 3 != 0)
        throw InputError(fmt::format("{}: mesh '{}' has {} indices, not a multiple of 3", desc.name, m.name,
                                     m.indices.size()));
    if (m.material < 0 || m.material >= static_cast<int>(desc.materials.size()))
        throw InputError(fmt::format("{}: mesh '{}' names material {}, which does not exist", desc.name,
                                     m.name, m.material));
    if (!m.normals.empty() && m.normals.size() != m.positions.size())
        throw InputError(fmt::format("{}: mesh '{}' has {} normals for {} positions", desc.name, m.name,
                                     m.normals.size(), m.positions.size()));
    for (uint32_t i : m.indices)
        if (i >= m.positions.size())
            throw InputError(fmt::format("{}: mesh '{}' index {} is out of range ({} positions)", desc.name,
                                         m.name, i, m.positions.size()));
    for (const Vec3& p : m.positions)
        if (!isCoordinate(p))
            throw InputError(fmt::format("{}: mesh '{}' has a vertex position that is not finite or beyond ±1e15",
                                         desc.name, m.name));
    if (!m.colours.empty() && m.colours.size() != m.positions.size())
        throw InputError(fmt::format("{}: mesh '{}' has {} vertex colours for {} positions", desc.name, m.name,
                                     m.colours.size(), m.positions.size()));
    for (const auto& c : m.colours)
        for (float x : c)
            if (!(x >= 0 && x <= 1))
                throw InputError(fmt::format("{}: mesh '{}' has a vertex colour outside [0, 1]", desc.name, m.name));
}

// The emitter a punctual light is, or none if it emits nothing; InputError for a bad one.
std::optional<Emitter> punctualEmitter(const LightDesc& l, const std::string& scene) {
    const Spectrum& i = l.intensity;
    if (!isFinite(l.position) || !isFinite(i) || i.x < 0 || i.y < 0 || i.z < 0)
        throw InputError(fmt::format("{}: a light has a non-finite or negative value", scene));
    if (!isFinite(l.direction) || !(lengthSquared(l.direction) > 0))
        throw InputError(fmt::format("{}: a light's direction is not finite or zero", scene));
    if (!(l.innerConeAngle >= 0 && l.innerConeAngle < l.outerConeAngle && l.outerConeAngle <= 0.5f * kPi))
        throw InputError(fmt::format("{}: a spot light's cone angles are not 0 <= inner < outer <= pi/2", scene));
    if (isBlack(i)) return std::nullopt;
    Emitter e;
    e.position = l.position;
    e.radiance = i;
    switch (l.kind) {
        case LightDesc::Kind::Point: e.kind = Emitter::Kind::Point; break;
        case LightDesc::Kind::Spot:
            e.kind = Emitter::Kind::Spot;
            e.axis = normalize(l.direction);
            e.cosInner = std::cos(l.innerConeAngle);
            e.cosOuter = std::cos(l.outerConeAngle);
            break;
        case LightDesc::Kind::Directional:
            e.kind = Emitter::Kind::Directional;
            e.axis = -normalize(l.direction);
            break;
    }
    return e;
}

// The environment a scene's map describes, or none; InputError for a bad map.
std::shared_ptr<const Environment> environment(const EnvironmentDesc& d, const std::string& scene) {
    if (!d.present()) return nullptr;
    if (d.width < 1 || d.height < 1 || d.texels.size() != size_t(d.width) * size_t(d.height))
        throw InputError(fmt::format("{}: the environment map's size does not match its texels", scene));
    for (const Spectrum& t : d.texels)
        if (!isFinite(t) || t.x < 0 || t.y < 0 || t.z < 0)
            throw InputError(fmt::format("{}: the environment has a non-finite or negative radiance", scene));
    return std::make_shared<const Environment>(d.width, d.height, d.texels);
}

// Per mesh, the transforms of all its instances; none for a mesh that appears as it is.
std::vector<std::optional<std::vector<Affine>>> placements(const SceneDesc& desc) {
    std::vector<std::optional<std::vector<Affine>>> out(desc.meshes.size());
    for (const InstancesDesc& in : desc.instances) {
        if (in.mesh < 0 || size_t(in.mesh) >= out.size())
            throw InputError(fmt::format("{}: instances name mesh {}, which does not exist", desc.name, in.mesh));
        for (const Affine& a : in.toWorld)
            if (!isFinite(a) || !isFinite(normalTransform(a)))
                throw InputError(fmt::format("{}: an instance of mesh '{}' has a transform that is not finite or "
                                             "singular", desc.name, desc.meshes[size_t(in.mesh)].name));
        auto& all = out[size_t(in.mesh)];
        if (!all) all.emplace();
        all->insert(all->end(), in.toWorld.begin(), in.toWorld.end());
    }
    return out;
}

// The mesh in world space as `toWorld` places it: normals through its inverse transpose, and the
// winding reversed by a mirroring transform so the front stays on the side the normals say.
MeshDesc placed(const MeshDesc& m, const Affine& toWorld) {
    MeshDesc out = m;
    const Affine normals = normalTransform(toWorld);
    for (Vec3& p : out.positions) p = transformPoint(toWorld, p);
    for (Vec3& n : out.normals) n = transformVector(normals, n);
    if (determinant(toWorld) < 0)
        for (size_t i = 0; i + 2 < out.indices.size(); i += 3) std::swap(out.indices[i + 1], out.indices[i + 2]);
    return out;
}

}  // namespace

Scene::Scene(SceneDesc desc, int width, int height, const WarningSink& warn)
    : name_(desc.name), sources_(desc.sources), materials_(desc.materials), camera_(CameraDesc{}, width, height) {
    for (const Material& m : materials_) {
        const std::string problem = validateMaterial(m);
        if (!problem.empty()) throw InputError(fmt::format("{}: material '{}': {}", name_, m.name, problem));
    }
    addMeshes(desc, warn);
    if (triangles_.empty()) throw InputError(fmt::format("{}: the scene has no triangles", name_));
    mayMisplaceHits_ = std::max(maxComponent(abs(lo_)), maxComponent(abs(hi_))) > kMisplacingScale;

    const Vec3 centre = (lo_ + hi_) * 0.5f;
    // A little beyond the bounds' corners: rays from emitters at infinity start outside the scene.
    const BoundingSphere sphere{centre, 0.5f * length(hi_ - lo_) * 1.01f + 1e-4f * maxComponent(abs(centre))};
    std::vector<Emitter> lights;
    for (const LightDesc& l : desc.lights)
        if (auto e = punctualEmitter(l, name_)) lights.push_back(*e);
    emitters_ = Emitters(triangles_, materials_, lights, environment(desc.environment, name_), sphere,
                         surfaceTextures_.get());
    if (emitters_.empty() && desc.environment.present())
        throw InputError(fmt::format("{}: the scene has no emitter but its environment, which is black everywhere: "
                                     "give one that emits, or add an emissive material or a light", name_));
    if (emitters_.empty())
        throw InputError(fmt::format("{}: the scene has no emitter: add an emissive material, a KHR_lights_punctual light, "
                                     "or an environment (--environment; environment= in Python)", name_));

    const CameraDesc cam = desc.camera.present ? desc.camera : frameBounds(lo_, hi_);
    if (!isFinite(cam.position) || !isFinite(cam.forward) || !isFinite(cam.up) || !(lengthSquared(cam.forward) > 0) ||
        !(lengthSquared(cross(cam.forward, cam.up)) > 0) || !(cam.yfov > 0 && cam.yfov < kPi))
        throw InputError(fmt::format("{}: the camera is degenerate (non-finite position or direction, or a bad yfov)", name_));
    cameraDesc_ = cam;
    camera_ = Camera(cam, width, height);
    buildBvh();
}

Scene::Memory Scene::memory() const {
    Memory m;
    m.triangles = triangles_.size() * kBytesPerTriangle;
    std::set<const TextureImage*> images;
    for (const Material& material : materials_) {
        if (!material.textures) continue;
        const MaterialTextures& t = *material.textures;
        for (const TextureSlot* slot : {&t.baseColor, &t.metallicRoughness, &t.normal, &t.emissive})
            if (*slot && images.insert(slot->texture->image().get()).second) m.textures += slot->texture->image()->bytes();
    }
    m.textures += surfaceTextures_->bytes();
    if (const Environment* map = emitters_.environmentMap()) m.environment = map->bytes();
    return m;
}

Scene::Scene(const Scene& base, int width, int height)
    : name_(base.name_), sources_(base.sources_), materials_(base.materials_), triangles_(base.triangles_),
      worldTriangles_(base.worldTriangles_), instances_(base.instances_), lo_(base.lo_), hi_(base.hi_),
      mayMisplaceHits_(base.mayMisplaceHits_),
      cameraDesc_(base.cameraDesc_), camera_(base.cameraDesc_, width, height), emitters_(base.emitters_),
      surfaceTextures_(base.surfaceTextures_), anyNormalTexture_(base.anyNormalTexture_),
      variesBsdfs_(base.variesBsdfs_), alphaMasks_(base.alphaMasks_),
      device_(base.device_),
      rtcScene_(base.rtcScene_) {
    rtcRetainDevice(device_);
    rtcRetainScene(rtcScene_);
}

// World-space triangles first (meshes used once, copies of emissive meshes), then each other
// instanced mesh once, in object space, with its instances.
void Scene::addMeshes(const SceneDesc& desc, const WarningSink& warn) {
    const std::vector<std::optional<std::vector<Affine>>> placement = placements(desc);
    std::vector<size_t> prototypes;
    size_t degenerate = 0;
    auto surfaceTextures = std::make_shared<SurfaceTextures>();
    for (size_t i = 0; i < desc.meshes.size(); ++i) {
        const MeshDesc& m = desc.meshes[i];
        checkMesh(desc, m);
        if (!placement[i])
            degenerate += addTriangles(m, *surfaceTextures);
        else if (!isBlack(desc.materials[size_t(m.material)].emission))
            for (const Affine& a : *placement[i]) degenerate += addTriangles(placed(m, a), *surfaceTextures);
        else if (!placement[i]->empty())
            prototypes.push_back(i);
    }
    worldTriangles_ = uint32_t(triangles_.size());
    for (size_t i : prototypes) {
        const auto first = uint32_t(triangles_.size());
        degenerate += addTriangles(desc.meshes[i], *surfaceTextures);
        const auto count = uint32_t(triangles_.size() - first);
        if (count == 0) continue;
        for (const Affine& a : *placement[i]) instances_.push_back({a, normalTransform(a), first, count});
    }
    surfaceTextures_ = std::move(surfaceTextures);
    anyNormalTexture_ = std::any_of(materials_.begin(), materials_.end(),
                                    [](const Material& m) { return m.textures && m.textures->normal; });
    variesBsdfs_ = surfaceTextures_->anyColours() ||
                   std::any_of(materials_.begin(), materials_.end(), [](const Material& m) { return m.textures != nullptr; });
    if (degenerate > 0) warn(fmt::format("{}: dropped {} degenerate (zero-area) triangles", name_, degenerate));
    findBounds();
}

// Appends the mesh's triangles as they are, their texture coordinates to `surfaces` if its material
// has textures and their corners' colours if the mesh has them; returns how many were degenerate
// and left out.
size_t Scene::addTriangles(const MeshDesc& m, SurfaceTextures& surfaces) {
    const MaterialTextures* textures = materials_[size_t(m.material)].textures.get();
    const auto first = uint32_t(triangles_.size());
    std::vector<TriangleTexCoords> texCoords;
    std::vector<TriangleColours> colours;
    size_t degenerate = 0;
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
        Triangle t;
        t.material = m.material;
        t.smooth = !m.normals.empty();
        for (int k = 0; k < 3; ++k) t.p[k] = m.positions[m.indices[i + k]];
        const Vec3 c = cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);
        // Zero-area or needle-thin beyond float precision: no normal, no area pdf. Drop it.
        if (!(length(c) > 0) || !isFinite(normalize(c))) {
            ++degenerate;
            continue;
        }
        const Vec3 ng = normalize(c);
        t.ng = ng;
        for (int k = 0; k < 3; ++k) {
            Vec3 n = t.smooth ? m.normals[m.indices[i + k]] : ng;
            if (!isFinite(n) || !(lengthSquared(n) > 0)) n = ng;
            t.n[k] = normalize(n);
        }
        if (textures) texCoords.push_back(triangleTexCoords(m, t, &m.indices[i]));
        if (!m.colours.empty())
            colours.push_back({{m.colours[m.indices[i]], m.colours[m.indices[i + 1]], m.colours[m.indices[i + 2]]}});
        triangles_.push_back(t);
    }
    surfaces.add(first, uint32_t(triangles_.size()) - first, textures, std::move(texCoords), std::move(colours));
    return degenerate;
}

// The box around the world-space triangles and every instance's, its corners where hits put them.
void Scene::findBounds() {
    lo_ = Vec3(3e38f);
    hi_ = Vec3(-3e38f);
    auto include = [&](Vec3 p) {
        if (!isCoordinate(p))
            throw InputError(fmt::format("{}: an instance places a vertex beyond ±1e15 or at a non-finite position", name_));
        lo_ = min(lo_, p);
        hi_ = max(hi_, p);
    };
    for (uint32_t i = 0; i < worldTriangles_; ++i)
        for (const Vec3& p : triangles_[i].p) include(p);
    for (const Instance& in : instances_)
        for (uint32_t i = in.firstTriangle; i < in.firstTriangle + in.triangleCount; ++i)
            for (const Vec3& p : triangles_[i].p) include(transformPoint(in.toWorld, p));
}

TriangleTexCoords Scene::triangleTexCoords(const MeshDesc& m, const Triangle& t, const uint32_t corners[3]) const {
    TriangleTexCoords r;
    for (size_t set = 0; set < 2; ++set)
        for (int k = 0; k < 3; ++k)
            r.corner[k][set] = m.texCoords[set].size() == m.positions.size() ? m.texCoords[set][corners[k]] : Vec2{};
    const MaterialTextures& textures = *materials_[size_t(m.material)].textures;
    if (!textures.normal) return r;
    const bool given = !m.tangents.empty() && m.tangents.size() == m.positions.size() &&
                       m.tangentSigns.size() == m.tangents.size();
    if (given) {
        for (int k = 0; k < 3; ++k) r.tangent[k] = m.tangents[corners[k]];
        r.bitangentSign = m.tangentSigns[corners[0]] < 0 ? -1.0f : 1.0f;
        return r;
    }
    const Vec2 uv[3] = {r.corner[0][size_t(textures.normal.texCoord)], r.corner[1][size_t(textures.normal.texCoord)],
                        r.corner[2][size_t(textures.normal.texCoord)]};
    Vec3 tangent;
    triangleTangent(t.p, uv, t.ng, tangent, r.bitangentSign);
    for (Vec3& c : r.tangent) c = tangent;
    return r;
}

const BsdfParams& Scene::variedBsdfAt(const Material& m, uint32_t triangle, Vec2 b,
                                      std::optional<BsdfParams>& scratch) const {
    const TriangleSurface surface = surfaceTextures_->find(triangle);
    if (!m.textures && !surface.colours) return m;
    kBsdfDerivations.add();
    BsdfParams& p = scratch.emplace(m.textures ? m.textures->at(m, surface.uvAt(b)) : BsdfParams(m));
    if (surface.colours) {
        const Texel c = surface.colours->at(b);
        p.albedo = p.albedo * Spectrum(c[0], c[1], c[2]);
    }
    return p;
}

namespace {

static_assert(sizeof(Affine) == 12 * sizeof(float), "Affine must be Embree's packed 3x4 column-major matrix");

// Triangles [first, first + count) as an Embree geometry, to be committed.
RTCGeometry triangleGeometry(RTCDevice device, const std::vector<Triangle>& triangles, size_t first, size_t count) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * count));
    auto* idx = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), count));
    for (size_t i = 0; i < count; ++i)
        for (int k = 0; k < 3; ++k) {
            const Vec3 p = triangles[first + i].p[k];
            v[9 * i + 3 * k + 0] = p.x;
            v[9 * i + 3 * k + 1] = p.y;
            v[9 * i + 3 * k + 2] = p.z;
            idx[3 * i + k] = static_cast<uint32_t>(3 * i + k);
        }
    return geom;
}

// Embree's filter for the triangles of alpha-masked materials, closest hits and shadow rays alike:
// a hit where the material's alpha (its vertex colour's included) is below its cutoff is no hit
// (the ray goes on through). Its user data is the geometry's AlphaMask: a primitive's triangle is
// `first` on from the geometry's.
void alphaMaskFilter(const RTCFilterFunctionNArguments* args) {
    const auto* mask = static_cast<const Scene::AlphaMask*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const uint32_t triangle = mask->first + RTCHitN_primID(args->hit, args->N, i);
        const Vec2 b{RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i)};
        if (mask->surfaces->find(triangle).holeAt(b)) args->valid[i] = 0;
    }
}

}  // namespace

void Scene::setAlphaFilters(RTCGeometryTy* geom, uint32_t first) {
    if (!surfaceTextures_->anyMasks()) return;  // no filter: opaque scenes pay nothing for masks
    alphaMasks_->push_back({surfaceTextures_.get(), first});
    rtcSetGeometryUserData(geom, &alphaMasks_->back());
    rtcSetGeometryIntersectFilterFunction(geom, &alphaMaskFilter);
    rtcSetGeometryOccludedFilterFunction(geom, &alphaMaskFilter);
}

// Geometry 0 holds the world-space triangles; geometry 1 + i is instance i, over an Embree scene
// per instanced mesh (the instances hold the references to it).
void Scene::buildBvh() {
    const std::string config = std::string("isa=") + kEmbreeIsas[embreeIsaLevel()];  // pinned: embree_isa.h
    device_ = rtcNewDevice(config.c_str());
    if (!device_) throw std::runtime_error("Embree: could not create a device");
    rtcScene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(rtcScene_, RTC_BUILD_QUALITY_HIGH);
    // One mask per geometry at most, at addresses that stay put: Embree keeps pointers to them.
    alphaMasks_ = std::make_shared<std::vector<AlphaMask>>();
    alphaMasks_->reserve(1 + instances_.size());
    if (worldTriangles_ > 0) {
        RTCGeometry geom = triangleGeometry(device_, triangles_, 0, worldTriangles_);
        setAlphaFilters(geom, 0);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(rtcScene_, geom, 0);
        rtcReleaseGeometry(geom);
    }
    RTCScene mesh = nullptr;
    for (size_t i = 0; i < instances_.size(); ++i) {
        const Instance& in = instances_[i];
        if (i == 0 || in.firstTriangle != instances_[i - 1].firstTriangle) {
            if (mesh) rtcReleaseScene(mesh);
            mesh = rtcNewScene(device_);
            rtcSetSceneBuildQuality(mesh, RTC_BUILD_QUALITY_HIGH);
            RTCGeometry geom = triangleGeometry(device_, triangles_, in.firstTriangle, in.triangleCount);
            setAlphaFilters(geom, in.firstTriangle);
            rtcCommitGeometry(geom);
            rtcAttachGeometry(mesh, geom);
            rtcReleaseGeometry(geom);
            rtcCommitScene(mesh);
        }
        RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(geom, mesh);
        rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, &in.toWorld);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(rtcScene_, geom, static_cast<unsigned>(1 + i));
        rtcReleaseGeometry(geom);
    }
    if (mesh) rtcReleaseScene(mesh);
    rtcCommitScene(rtcScene_);
}

Scene::~Scene() {
    if (rtcScene_) rtcReleaseScene(rtcScene_);
    if (device_) rtcReleaseDevice(device_);
}

namespace {

// n, or −n: the one on the side of ng.
Vec3 orient(Vec3 n, Vec3 ng) { return dot(n, ng) < 0 ? -n : n; }

// A mapped normal n kept above the geometric surface: n itself, or, where the normal texture
// tilts it to or past the plane of ng, the direction in that plane it leans toward raised to
// kMinMappedCosine above it. (Flipping it instead, as for interpolated normals, would turn the
// bump the other way.)
constexpr float kMinMappedCosine = 0.01f;
Vec3 keepAbove(Vec3 n, Vec3 ng) {
    const float c = dot(n, ng);
    if (c >= kMinMappedCosine) return n;
    const Vec3 along = n - ng * c;
    if (!(lengthSquared(along) > 0)) return ng;
    return normalize(normalize(along) * std::sqrt(1.0f - kMinMappedCosine * kMinMappedCosine) + ng * kMinMappedCosine);
}

// The corners' normals n0, n1, n2 blended at barycentrics (u, v), unit, on the side of ng.
Vec3 blendNormals(Vec3 n0, Vec3 n1, Vec3 n2, float u, float v, Vec3 ng) {
    const Vec3 n = n0 * (1.0f - u - v) + n1 * u + n2 * v;
    return lengthSquared(n) > 0 ? orient(normalize(n), ng) : ng;
}

}  // namespace

bool Scene::hasNormalTexture(const Triangle& t) const {
    if (!anyNormalTexture_) return false;  // no lookup of the material in scenes without one
    const MaterialTextures* textures = materials_[size_t(t.material)].textures.get();
    return textures && textures->normal;
}

Vec3 Scene::shadingNormal(uint32_t triangle, float u, float v) const {
    const Triangle& t = triangles_[triangle];
    const Vec3 ng = t.geometricNormal();
    const bool mapped = hasNormalTexture(t);
    if (!t.smooth && !mapped) return ng;
    const Vec3 n = blendNormals(t.n[0], t.n[1], t.n[2], u, v, ng);
    if (!mapped) return n;
    const TriangleTexCoords& r = *surfaceTextures_->find(triangle).texCoords;
    const Vec3 tangent = r.tangent[0] * (1.0f - u - v) + r.tangent[1] * u + r.tangent[2] * v;
    const MaterialTextures& textures = *materials_[size_t(t.material)].textures;
    return keepAbove(perturbNormal(n, tangent, r.bitangentSign, textures.tangentNormalAt(r.at({u, v}))), ng);
}

std::optional<SurfacePoint> Scene::intersect(Vec3 origin, Vec3 dir, float tMax) const {
    // Debian's Embree asserts on invalid rays; a non-finite ray (which validation should have made
    // impossible) must cost a sample, never the process.
    if (!isFinite(origin) || !isFinite(dir)) return std::nullopt;
    kClosestHitRays.add();
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray.org_x = origin.x;
    rh.ray.org_y = origin.y;
    rh.ray.org_z = origin.z;
    rh.ray.dir_x = dir.x;
    rh.ray.dir_y = dir.y;
    rh.ray.dir_z = dir.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = tMax;
    rh.ray.mask = 0xffffffffu;
    rh.ray.time = 0.0f;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rtcScene_, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return hitPoint(rh.hit.instID[0], rh.hit.primID, rh.hit.u, rh.hit.v, origin, dir, rh.ray.tfar);
}

void Scene::intersect8(Vec3 origin, std::span<const Vec3> dirs, std::span<std::optional<SurfacePoint>> hits) const {
    if (dirs.size() > 8 || hits.size() < dirs.size()) throw std::logic_error("Scene::intersect8: at most 8 rays, a hit each");
    alignas(32) RTCRayHit8 packet;
    alignas(32) int valid[8];
    int lanes = 0;
    for (size_t i = 0; i < 8; ++i) {
        valid[i] = i < dirs.size() && isFinite(origin) && isFinite(dirs[i]) ? -1 : 0;
        if (!valid[i]) continue;
        ++lanes;
        packet.ray.org_x[i] = origin.x;
        packet.ray.org_y[i] = origin.y;
        packet.ray.org_z[i] = origin.z;
        packet.ray.dir_x[i] = dirs[i].x;
        packet.ray.dir_y[i] = dirs[i].y;
        packet.ray.dir_z[i] = dirs[i].z;
        packet.ray.tnear[i] = 0.0f;
        packet.ray.tfar[i] = 3.0e38f;
        packet.ray.mask[i] = 0xffffffffu;
        packet.ray.time[i] = 0.0f;
        packet.ray.flags[i] = 0;
        packet.ray.id[i] = 0;
        packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    kClosestHitRays.add(uint64_t(lanes));
    if (lanes > 0) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        rtcIntersect8(valid, rtcScene_, &ctx, &packet);
    }
    for (size_t i = 0; i < dirs.size(); ++i) {
        if (valid[i] && packet.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID)
            hits[i] = hitPoint(packet.hit.instID[0][i], packet.hit.primID[i], packet.hit.u[i], packet.hit.v[i], origin,
                               dirs[i], packet.ray.tfar[i]);
        else
            hits[i].reset();
    }
}

SurfacePoint Scene::surfacePoint(uint32_t triangle, float u, float v, float tHit) const {
    SurfacePoint sp;
    sp.triangle = triangle;
    sp.bary = {u, v};
    sp.t = tHit;
    const Triangle& t = triangles_[triangle];
    // From barycentrics rather than origin + t·dir: the point lies on the triangle's plane to
    // within rounding of its own coordinates, whatever the ray's length.
    sp.p = t.p[0] * (1.0f - u - v) + t.p[1] * u + t.p[2] * v;
    sp.ng = t.geometricNormal();
    sp.ns = t.smooth || anyNormalTexture_ ? shadingNormal(triangle, u, v) : sp.ng;  // flat shading without a call
    return sp;
}

namespace {

// The hit point as precisely as floats allow. surfacePoint's, from barycentrics, is off by about
// 2^-24 of the triangle's coordinates and edges (Embree's u and v carry that error); org + t·dir by
// about 2^-24 of |org| + t. Where a triangle is over 1024 times the ray's reach (a ground of 10 km
// seen from a millimetre away, where the barycentric point lands up to 0.5 mm off, in or out of a
// small object's shadow), the ray's point is taken, moved in double onto the triangle's plane so
// that it lies on it as the barycentric point does. Only a scene with coordinates beyond
// kMisplacingScale asks (Scene::mayMisplaceHits_).
Vec3 nearerHitPoint(const Triangle& t, Vec3 barycentric, Vec3 org, Vec3 dir, float tHit) {
    constexpr float kFarLarger = 1024;
    const float reach = (maxComponent(abs(org)) + tHit * maxComponent(abs(dir))) * kFarLarger;
    const float triangleScale = std::max({maxComponent(abs(t.p[0])), maxComponent(abs(t.p[1])), maxComponent(abs(t.p[2]))});
    if (!(reach < triangleScale)) return barycentric;
    auto d = [](Vec3 a) { return std::array<double, 3>{a.x, a.y, a.z}; };
    const auto p0 = d(t.p[0]), p1 = d(t.p[1]), p2 = d(t.p[2]), o = d(org), w = d(dir);
    const std::array<double, 3> e1{p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, e2{p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    const std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (!(nn > 0)) return barycentric;
    std::array<double, 3> q{};
    for (int k = 0; k < 3; ++k) q[size_t(k)] = o[size_t(k)] + w[size_t(k)] * double(tHit);
    const double off = ((q[0] - p0[0]) * n[0] + (q[1] - p0[1]) * n[1] + (q[2] - p0[2]) * n[2]) / nn;
    return {float(q[0] - off * n[0]), float(q[1] - off * n[1]), float(q[2] - off * n[2])};
}

}  // namespace

// An instance's triangle as the flattened mesh would have it: the point through toWorld, the
// normals through normalToWorld, each corner's unit before they are blended (as the loader leaves
// the normals of a mesh it places in world space).
SurfacePoint Scene::hitPoint(uint32_t instance, uint32_t primitive, float u, float v, Vec3 org, Vec3 dir, float tHit) const {
    if (instance == RTC_INVALID_GEOMETRY_ID) {
        SurfacePoint sp = surfacePoint(primitive, u, v, tHit);
        if (mayMisplaceHits_) sp.p = nearerHitPoint(triangles_[primitive], sp.p, org, dir, tHit);
        return sp;
    }
    const Instance& in = instances_[instance - 1];
    SurfacePoint sp = surfacePoint(in.firstTriangle + primitive, u, v, tHit);
    const Triangle& t = triangles_[sp.triangle];
    auto normal = [&](Vec3 n) { return normalize(transformVector(in.normalToWorld, n)); };
    sp.p = transformPoint(in.toWorld, sp.p);
    sp.ng = normal(t.ng);
    if (hasNormalTexture(t))  // perturbed in the mesh's space, then carried to the world's
        sp.ns = orient(normal(sp.ns), sp.ng);
    else
        sp.ns = t.smooth ? blendNormals(normal(t.n[0]), normal(t.n[1]), normal(t.n[2]), u, v, sp.ng) : sp.ng;
    return sp;
}

namespace {

// Whether nothing lies along from + t·d for t in (0, tFar): one occlusion ray.
bool unoccludedRay(RTCScene scene, Vec3 from, Vec3 d, float tFar) {
    kShadowRays.add();
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay ray;
    ray.org_x = from.x;
    ray.org_y = from.y;
    ray.org_z = from.z;
    ray.dir_x = d.x;
    ray.dir_y = d.y;
    ray.dir_z = d.z;
    ray.tnear = 0.0f;
    ray.tfar = tFar;
    ray.mask = 0xffffffffu;
    ray.time = 0.0f;
    ray.flags = 0;
    rtcOccluded1(scene, &ctx, &ray);
    return ray.tfar >= 0.0f;  // Embree sets tfar to -inf on a hit
}

}  // namespace

bool Scene::unoccluded(Vec3 a, Vec3 aNormal, Vec3 b, Vec3 bNormal) const {
    const bool aSurface = lengthSquared(aNormal) > 0, bSurface = lengthSquared(bNormal) > 0;
    const Vec3 from = aSurface ? offsetRayOrigin(a, aNormal, b - a) : a;
    const Vec3 to = bSurface ? offsetRayOrigin(b, bNormal, a - b) : b;
    if (!isFinite(from) || !isFinite(to)) return false;
    return unoccludedRay(rtcScene_, from, to - from, 1.0f);  // the direction spans the whole segment between the offset ends
}

bool Scene::unoccludedToward(Vec3 p, Vec3 normal, Vec3 dir) const {
    const Vec3 from = lengthSquared(normal) > 0 ? offsetRayOrigin(p, normal, dir) : p;
    if (!isFinite(from) || !isFinite(dir)) return false;
    return unoccludedRay(rtcScene_, from, dir, 3.0e38f);
}

namespace {

// The distance along the ray from `origin` in `dir` to the first surface that does not scatter
// through a delta lobe, following mirrors and glass (refraction where there is a choice) for a
// few bounces: a plane mirror or pane leaves a pixel's footprint the size it has at the unfolded
// distance. 0 if the ray leaves the scene or stays among deltas.
float distanceToFirstNonDelta(const Scene& scene, Vec3 origin, Vec3 dir) {
    float travelled = 0;
    for (int bounce = 0; bounce < 8; ++bounce) {
        const auto hit = scene.intersect(origin, dir);
        if (!hit) return 0.0f;
        travelled += hit->t;
        const Material& m = scene.materialOf(hit->triangle);
        if (!isDelta(m)) return travelled;
        const Frame frame(hit->ns);
        const auto s = sampleBsdf(m, frame.toLocal(-dir), {0.5f, 0.5f}, 0.9999f, TransportMode::Radiance);
        if (!s) return 0.0f;
        dir = frame.toWorld(s->wi);
        origin = offsetRayOrigin(hit->p, hit->ng, dir);
    }
    return 0.0f;
}

}  // namespace

float medianPixelFootprint(const Scene& scene) {
    constexpr int kGrid = 16;
    const Camera& cam = scene.camera();
    std::vector<float> widths;
    for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) {
            const Vec2 raster{(i + 0.5f) * cam.width() / kGrid, (j + 0.5f) * cam.height() / kGrid};
            const Vec3 d = cam.direction(raster);
            const Vec3 next = cam.direction({raster.x + 1.0f, raster.y});
            const float distance = distanceToFirstNonDelta(scene, cam.position(), d);
            if (distance > 0) widths.push_back(distance * length(next - d));
        }
    if (widths.empty()) return 0.0f;
    const auto middle = widths.begin() + widths.size() / 2;
    std::nth_element(widths.begin(), middle, widths.end());
    return *middle;
}

}  // namespace tripath
