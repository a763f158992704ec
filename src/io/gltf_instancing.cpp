// Reading EXT_mesh_gpu_instancing (gltf_instancing.h).
#include "io/gltf_instancing.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "io/gltf_transforms.h"

namespace tripath::gltf {

namespace {

// One attribute's floats, `components` per instance; empty when the extension does not name it.
std::vector<float> readAttribute(const tinygltf::Value& attributes, const char* name, int components, const std::string& what,
                                 const Accessors& accessors, const Report& report) {
    if (!attributes.Has(name)) return {};
    const tinygltf::Value& index = attributes.Get(name);
    if (!index.IsInt()) report.fail(what + " " + name + " is not an accessor index");
    return accessors.readFloats(index.GetNumberAsInt(), components, what + " " + name);
}

bool allFinite(const std::vector<float>& values) {
    for (float x : values)
        if (!std::isfinite(x)) return false;
    return true;
}

}  // namespace

std::optional<std::vector<TrsDesc>> readInstances(const tinygltf::Node& node, int index, const Accessors& accessors,
                                                  const Report& report) {
    const auto ext = node.extensions.find(kInstancingExtension);
    if (ext == node.extensions.end()) return std::nullopt;
    const std::string what = "node " + std::to_string(index) + " " + kInstancingExtension;
    if (!ext->second.IsObject() || !ext->second.Get("attributes").IsObject())
        report.fail(what + " has no attributes object");
    const tinygltf::Value& attributes = ext->second.Get("attributes");
    const std::vector<float> t = readAttribute(attributes, "TRANSLATION", 3, what, accessors, report);
    const std::vector<float> r = readAttribute(attributes, "ROTATION", 4, what, accessors, report);
    const std::vector<float> s = readAttribute(attributes, "SCALE", 3, what, accessors, report);
    const size_t count = std::max({t.size() / 3, r.size() / 4, s.size() / 3});
    if (count == 0) report.fail(what + " has no TRANSLATION, ROTATION or SCALE instances");
    for (const auto& [values, components, name] : {std::tuple{&t, 3u, "TRANSLATION"}, std::tuple{&r, 4u, "ROTATION"},
                                                   std::tuple{&s, 3u, "SCALE"}}) {
        if (!values->empty() && values->size() != count * components)
            report.fail(what + " accessors disagree: " + name + " has " + std::to_string(values->size() / components) +
                        " instances, another " + std::to_string(count));
        if (!allFinite(*values)) report.fail(what + " " + name + " has a non-finite value");
    }
    std::vector<TrsDesc> out(count);
    for (size_t i = 0; i < count; ++i) {
        TrsDesc& d = out[i];
        if (!t.empty()) d.translation = {t[3 * i], t[3 * i + 1], t[3 * i + 2]};
        if (!r.empty())
            for (int k = 0; k < 4; ++k) d.rotation[k] = r[4 * i + size_t(k)];
        if (!s.empty()) d.scale = {s[3 * i], s[3 * i + 1], s[3 * i + 2]};
        const std::string instance = what + " instance " + std::to_string(i);
        if (!(std::abs(d.rotation[0]) + std::abs(d.rotation[1]) + std::abs(d.rotation[2]) + std::abs(d.rotation[3]) > 0))
            report.fail(instance + " rotation quaternion has zero length");
        if (collapsesSpace(instanceMatrix(d))) report.fail(instance + " has a zero scale (it collapses the mesh)");
    }
    return out;
}

glm::dmat4 instanceMatrix(const TrsDesc& trs) {
    const glm::dquat rotation(trs.rotation[3], trs.rotation[0], trs.rotation[1], trs.rotation[2]);  // w first
    const Vec3 t = trs.translation, s = trs.scale;
    return trsMatrix({t.x, t.y, t.z}, glm::normalize(rotation), {s.x, s.y, s.z});
}

}  // namespace tripath::gltf
