// The checks and message helpers that the pieces of the glTF loader share (gltf_checks.h).
#include "io/gltf_checks.h"

#include <cmath>
#include <sstream>

namespace tripath::gltf {

namespace {

// Extensions whose content the loader reads.
const std::set<std::string> kHandledExtensions = {
    "KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
    "KHR_materials_emissive_strength", "KHR_materials_volume", "EXT_mesh_gpu_instancing", "KHR_texture_transform"};

}  // namespace

std::string formatNumber(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

std::string excerpt(const std::string& text, size_t maxBytes) {
    if (text.size() <= maxBytes) return text;
    size_t cut = maxBytes;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // a UTF-8 continuation byte
    return text.substr(0, cut) + "... (" + std::to_string(text.size()) + " bytes)";
}

std::string quoted(const std::string& text, size_t maxBytes) {
    std::string out = "\"";
    for (const char c : excerpt(text, maxBytes)) {
        const auto byte = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (byte < 0x20 || byte == 0x7f) {
            static const char* const kHex = "0123456789abcdef";
            out += "\\x";
            out += kHex[byte >> 4];
            out += kHex[byte & 15];
        } else {
            out += c;
        }
    }
    return out + "\"";
}

bool allFinite(const std::vector<double>& values) {
    for (double x : values)
        if (!std::isfinite(float(x))) return false;
    return true;
}

Vec3 finiteVec3(const std::vector<double>& values, Vec3 fallback, const std::string& what, const Report& report) {
    if (values.empty()) return fallback;
    if (values.size() < 3) report.fail(what + " has " + std::to_string(values.size()) + " components");
    if (!allFinite(values)) report.fail(what + " is not finite");
    return {float(values[0]), float(values[1]), float(values[2])};
}

bool isHandledExtension(const std::string& name) { return kHandledExtensions.count(name) > 0; }

}  // namespace tripath::gltf
