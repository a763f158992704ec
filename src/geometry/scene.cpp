#include "geometry/scene.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/embree_isa.h"
#include "core/error.h"
#include "core/stats.h"

namespace tripath {

namespace {
constexpr Counter kClosestHitRays{Event::ClosestHitRays};
constexpr Counter kShadowRays{Event::ShadowRays};
}  // namespace

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
    // Beyond 1e15 m, squared distances between vertices (r² in g and every area pdf) come close to
    // float's range; nothing physical needs such coordinates.
    constexpr float kMaxCoordinate = 1e15f;
    for (const Vec3& p : m.positions)
        if (!isFinite(p) || maxComponent(abs(p)) > kMaxCoordinate)
            throw InputError(fmt::format("{}: mesh '{}' has a vertex position that is not finite or beyond ±1e15",
                                         desc.name, m.name));
}

}  // namespace

Scene::Scene(SceneDesc desc, int width, int height, const WarningSink& warn)
    : name_(desc.name), materials_(desc.materials), camera_(CameraDesc{}, width, height) {
    for (const Material& m : materials_) {
        const std::string problem = validateMaterial(m);
        if (!problem.empty()) throw InputError(fmt::format("{}: material '{}': {}", name_, m.name, problem));
    }
    addMeshes(desc, warn);
    if (triangles_.empty()) throw InputError(fmt::format("{}: the scene has no triangles", name_));

    std::vector<Emitter> points;
    for (const PointLightDesc& l : desc.pointLights) {
        if (!isFinite(l.position) || !isFinite(l.intensity) || l.intensity.x < 0 || l.intensity.y < 0 ||
            l.intensity.z < 0)
            throw InputError(fmt::format("{}: a point light has a non-finite or negative value", name_));
        if (isBlack(l.intensity)) continue;
        Emitter e;
        e.position = l.position;
        e.radiance = l.intensity;
        points.push_back(e);
    }
    emitters_ = Emitters(triangles_, materials_, points, surfaceTextures_.get());
    if (emitters_.empty()) throw InputError(fmt::format("{}: the scene has no emitter (nothing emits light)", name_));

    const CameraDesc cam = desc.camera.present ? desc.camera : frameBounds(lo_, hi_);
    if (!isFinite(cam.position) || !isFinite(cam.forward) || !isFinite(cam.up) || !(lengthSquared(cam.forward) > 0) ||
        !(lengthSquared(cross(cam.forward, cam.up)) > 0) || !(cam.yfov > 0 && cam.yfov < kPi))
        throw InputError(fmt::format("{}: the camera is degenerate (non-finite position or direction, or a bad yfov)", name_));
    cameraDesc_ = cam;
    camera_ = Camera(cam, width, height);
    buildBvh();
}

Scene::Scene(const Scene& base, int width, int height)
    : name_(base.name_), materials_(base.materials_), triangles_(base.triangles_), lo_(base.lo_), hi_(base.hi_),
      cameraDesc_(base.cameraDesc_), camera_(base.cameraDesc_, width, height), emitters_(base.emitters_),
      surfaceTextures_(base.surfaceTextures_), anyNormalTexture_(base.anyNormalTexture_), device_(base.device_),
      rtcScene_(base.rtcScene_) {
    rtcRetainDevice(device_);
    rtcRetainScene(rtcScene_);
}

void Scene::addMeshes(const SceneDesc& desc, const WarningSink& warn) {
    lo_ = Vec3(3e38f);
    hi_ = Vec3(-3e38f);
    size_t degenerate = 0;
    auto surfaceTextures = std::make_shared<SurfaceTextures>();
    for (const MeshDesc& m : desc.meshes) {
        checkMesh(desc, m);
        const MaterialTextures* textures = materials_[size_t(m.material)].textures.get();
        const auto first = uint32_t(triangles_.size());
        std::vector<TriangleTexCoords> texCoords;
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
                lo_ = min(lo_, t.p[k]);
                hi_ = max(hi_, t.p[k]);
            }
            if (textures) texCoords.push_back(triangleTexCoords(m, t, &m.indices[i]));
            triangles_.push_back(t);
        }
        if (textures) surfaceTextures->add(first, textures, std::move(texCoords));
    }
    surfaceTextures_ = std::move(surfaceTextures);
    anyNormalTexture_ = std::any_of(materials_.begin(), materials_.end(),
                                    [](const Material& m) { return m.textures && m.textures->normal; });
    if (degenerate > 0) warn(fmt::format("{}: dropped {} degenerate (zero-area) triangles", name_, degenerate));
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

TexCoords Scene::texCoords(uint32_t triangle, Vec2 b) const {
    const TriangleTexCoords* r = surfaceTextures_->find(triangle);
    return r ? r->at(b) : TexCoords{};
}

namespace {

// Embree's filter for the triangles of alpha-masked materials, closest hits and shadow rays alike:
// a hit where the material's alpha is below its cutoff is no hit (the ray goes on through).
void alphaMaskFilter(const RTCFilterFunctionNArguments* args) {
    const auto* surfaces = static_cast<const SurfaceTextures*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const uint32_t triangle = RTCHitN_primID(args->hit, args->N, i);
        const MaterialTextures* textures = surfaces->materialOf(triangle);
        if (!textures || !textures->masks()) continue;
        const Vec2 b{RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i)};
        if (textures->holeAt(surfaces->find(triangle)->at(b))) args->valid[i] = 0;
    }
}

}  // namespace

void Scene::setAlphaFilters(RTCGeometryTy* geom) const {
    if (!surfaceTextures_->anyMasks()) return;  // no filter: opaque scenes trace as fast as ever
    rtcSetGeometryUserData(geom, const_cast<SurfaceTextures*>(surfaceTextures_.get()));
    rtcSetGeometryIntersectFilterFunction(geom, &alphaMaskFilter);
    rtcSetGeometryOccludedFilterFunction(geom, &alphaMaskFilter);
}

void Scene::buildBvh() {
    const std::string config = std::string("isa=") + kEmbreeIsas[embreeIsaLevel()];  // pinned: embree_isa.h
    device_ = rtcNewDevice(config.c_str());
    if (!device_) throw std::runtime_error("Embree: could not create a device");
    rtcScene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(rtcScene_, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), 3 * triangles_.size()));
    auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(uint32_t), triangles_.size()));
    for (size_t i = 0; i < triangles_.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            v[9 * i + 3 * k + 0] = triangles_[i].p[k].x;
            v[9 * i + 3 * k + 1] = triangles_[i].p[k].y;
            v[9 * i + 3 * k + 2] = triangles_[i].p[k].z;
            idx[3 * i + k] = static_cast<uint32_t>(3 * i + k);
        }
    setAlphaFilters(geom);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(rtcScene_, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(rtcScene_);
}

Scene::~Scene() {
    if (rtcScene_) rtcReleaseScene(rtcScene_);
    if (device_) rtcReleaseDevice(device_);
}

Vec3 Scene::shadingNormal(uint32_t triangle, float u, float v) const {
    const Triangle& t = triangles_[triangle];
    const Vec3 ng = t.geometricNormal();
    if (!t.smooth && !anyNormalTexture_) return ng;  // flat shading without a lookup of the material
    const MaterialTextures* textures = materials_[size_t(t.material)].textures.get();
    const bool mapped = textures && textures->normal;
    if (!t.smooth && !mapped) return ng;
    Vec3 n = t.n[0] * (1.0f - u - v) + t.n[1] * u + t.n[2] * v;
    n = lengthSquared(n) > 0 ? normalize(n) : ng;
    if (mapped) {
        const TriangleTexCoords& r = *surfaceTextures_->find(triangle);
        const Vec3 tangent = r.tangent[0] * (1.0f - u - v) + r.tangent[1] * u + r.tangent[2] * v;
        n = perturbNormal(n, tangent, r.bitangentSign, textures->tangentNormalAt(r.at({u, v})));
    }
    return dot(n, ng) < 0 ? -n : n;
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
    rtcIntersect1(rtcScene_, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return surfacePoint(rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar);
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
            hits[i] = surfacePoint(packet.hit.primID[i], packet.hit.u[i], packet.hit.v[i], packet.ray.tfar[i]);
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
    sp.ns = shadingNormal(triangle, u, v);
    return sp;
}

bool Scene::unoccluded(Vec3 a, Vec3 aNormal, Vec3 b, Vec3 bNormal) const {
    const bool aSurface = lengthSquared(aNormal) > 0, bSurface = lengthSquared(bNormal) > 0;
    const Vec3 from = aSurface ? offsetRayOrigin(a, aNormal, b - a) : a;
    const Vec3 to = bSurface ? offsetRayOrigin(b, bNormal, a - b) : b;
    if (!isFinite(from) || !isFinite(to)) return false;
    kShadowRays.add();
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay ray;
    const Vec3 d = to - from;
    ray.org_x = from.x;
    ray.org_y = from.y;
    ray.org_z = from.z;
    ray.dir_x = d.x;
    ray.dir_y = d.y;
    ray.dir_z = d.z;
    ray.tnear = 0.0f;
    ray.tfar = 1.0f;  // the direction spans the whole segment between the offset ends
    ray.mask = 0xffffffffu;
    ray.time = 0.0f;
    ray.flags = 0;
    rtcOccluded1(rtcScene_, &ctx, &ray);
    return ray.tfar >= 0.0f;  // Embree sets tfar to -inf on a hit
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
