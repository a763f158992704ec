#include "evaluation/reference_file.h"

#include <fmt/format.h>

#include <climits>
#include <cstdint>
#include <limits>

#include "core/error.h"
#include "core/number_text.h"
#include "integrators/render.h"
#include "io/gltf_checks.h"
#include "requests/scene_identity.h"

namespace tripath::evaluation {

std::optional<std::string> ReferenceFile::value(const std::string& key) const {
    for (const auto& [k, v] : meta)
        if (k == key) return v;
    return std::nullopt;
}

uint64_t ReferenceFile::wholeNumber(const std::string& key, uint64_t max, uint64_t absent) const {
    const auto v = value(key);
    if (!v) return absent;
    const auto number = parseWholeNumber(*v, max);
    if (!number)
        throw InputError(
            fmt::format("'{}': {} is '{}', not a whole number from 0 to {}", path, key, gltf::excerpt(*v), max));
    return *number;
}

int ReferenceFile::spp() const { return int(wholeNumber("tripath:spp", INT_MAX, 0)); }

double ReferenceFile::seconds() const {
    const auto v = value("tripath:seconds");
    if (!v) return 0;
    const auto number = parseNonNegative(*v, std::numeric_limits<double>::max());
    if (!number)
        throw InputError(
            fmt::format("'{}': tripath:seconds is '{}', not a finite number from 0", path, gltf::excerpt(*v)));
    return *number;
}

std::string ReferenceFile::description() const {
    const auto integrator = value("tripath:integrator");
    if (!integrator) return "external reference";
    return fmt::format("{}, {} spp, {:.0f} s", *integrator, spp(), seconds());
}

StreamDomain streamDomain(const ReferenceFile& ref) {
    const auto v = ref.value("tripath:streams");
    if (!v || *v == "render") return StreamDomain::CameraSample;
    if (*v == "reference") return StreamDomain::Reference;
    throw InputError(fmt::format("'{}': tripath:streams is '{}', neither 'render' nor 'reference'", ref.path, *v));
}

ReferenceFile readReference(const std::string& path) {
    ReferenceFile ref;
    ref.path = path;
    ref.image = readExr(path, &ref.meta);
    // The numbers it records, checked before any rendering rather than where each is used.
    ref.spp();
    ref.seconds();
    ref.wholeNumber("tripath:next-pass", kMaxFirstPass, 0);
    ref.wholeNumber("tripath:dropped-samples", UINT64_MAX, 0);
    ref.wholeNumber("tripath:seed", UINT64_MAX, 0);
    return ref;
}

void requireSize(const ReferenceFile& ref, int width, int height) {
    if (ref.image.width != width || ref.image.height != height)
        throw InputError(fmt::format("reference '{}' is {}x{}, but this render is {}x{} (--width/--height)", ref.path,
                                     ref.image.width, ref.image.height, width, height));
}

void requireSettings(const ReferenceFile& ref, const std::vector<std::pair<std::string, std::string>>& expected,
                     bool allowMissing) {
    for (const auto& [key, want] : expected) {
        const auto got = ref.value(key);
        if (!got && allowMissing) continue;
        if (!got)
            throw InputError(fmt::format("'{}' has no {} metadata: not a tripath reference (choose another file)",
                                         ref.path, key));
        if (key == kSceneFilesKey) {
            const std::string difference = sceneFilesDifference(*got, want);
            if (!difference.empty())
                throw InputError(
                    fmt::format("reference '{}' was made from other scene files: {}", ref.path, difference));
            continue;
        }
        if (*got != want)
            throw InputError(fmt::format("reference '{}' has {} {}, but this render has {} {}", ref.path,
                                         key.substr(8), *got, key.substr(8), want));
    }
}

void setMetadata(Metadata& meta, const std::string& key, const std::string& value) {
    for (auto& [k, v] : meta)
        if (k == key) {
            v = value;
            return;
        }
    meta.emplace_back(key, value);
}

}  // namespace tripath::evaluation
