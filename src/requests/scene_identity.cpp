#include "requests/scene_identity.h"

#include <string_view>
#include <utility>

#include "core/fnv1a.h"
#include "io/gltf_checks.h"

namespace tripath {

namespace {

constexpr std::string_view kSeparator = "; ";

// A name as a record holds it: one entry of the list, whatever the file is called.
std::string recordedName(const std::string& name) {
    std::string out = gltf::excerpt(name);
    for (char& c : out)
        if (c == ';' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return out;
}

// A record's entries as (name, hash text); an entry without a space is all name, with no hash.
std::vector<std::pair<std::string, std::string>> entries(const std::string& record) {
    std::vector<std::pair<std::string, std::string>> out;
    for (size_t start = 0; start < record.size();) {
        size_t end = record.find(kSeparator, start);
        if (end == std::string::npos) end = record.size();
        const std::string entry = record.substr(start, end - start);
        const size_t space = entry.rfind(' ');
        if (space == std::string::npos)
            out.emplace_back(entry, "");
        else
            out.emplace_back(entry.substr(0, space), entry.substr(space + 1));
        start = end + kSeparator.size();
    }
    return out;
}

}  // namespace

std::string sceneFilesText(const std::vector<SourceFile>& sources) {
    std::string out;
    for (const SourceFile& s : sources) {
        if (!out.empty()) out += kSeparator;
        out += recordedName(s.name) + " " + hashText(s.hash);
    }
    return out;
}

std::string sceneFilesDifference(const std::string& recorded, const std::string& current) {
    const auto before = entries(recorded), now = entries(current);
    for (size_t i = 0; i < before.size() && i < now.size(); ++i) {
        const auto& [was, wasHash] = before[i];
        const auto& [is, isHash] = now[i];
        if (wasHash.empty() || wasHash != isHash)
            return was == is ? gltf::excerpt(was) + " changed" : gltf::excerpt(was) + " is now " + gltf::excerpt(is);
    }
    if (now.size() > before.size()) return gltf::excerpt(now[before.size()].first) + " is new";
    if (before.size() > now.size()) return gltf::excerpt(before[now.size()].first) + " is gone";
    return "";
}

}  // namespace tripath
