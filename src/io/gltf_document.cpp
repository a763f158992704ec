// The container, JSON, nesting and version checks that run before tinygltf reads a glTF file
// (gltf_document.h).
#include "io/gltf_document.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace tripath::gltf {

namespace {

constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON", little-endian
constexpr size_t kGlbHeader = 12, kChunkHeader = 8;
// nlohmann's description of a syntax error runs to about 100 bytes (its expected tokens).
constexpr size_t kProblemLength = 120;

uint32_t readU32(const std::vector<char>& bytes, size_t offset) {
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + offset, 4);
    return value;
}

// What a file that is not a GLB probably is, for the message that refuses it.
std::string notGlbHint(const std::vector<char>& bytes) {
    const auto first = std::find_if(bytes.begin(), bytes.end(), [](char c) { return !std::isspace(uint8_t(c)); });
    return first != bytes.end() && *first == '{' ? "; it looks like JSON: name it .gltf" : "";
}

// nlohmann's own words for what is wrong, without its prefix and position and without the text it
// quotes ("last read: '...'", which can be a whole line of the file): e.g. "syntax error while
// parsing object key - unexpected end of input; expected string literal".
std::string jsonProblem(const std::string& what) {
    const size_t start = what.find("syntax error");
    if (start == std::string::npos) return "";
    std::string problem = what.substr(start);
    const size_t quote = problem.find("; last read: '");
    if (quote != std::string::npos) {
        const size_t expected = problem.rfind("; expected ");
        const bool expectedFollows = expected != std::string::npos && expected > quote;
        problem = problem.substr(0, quote) + (expectedFollows ? problem.substr(expected) : "");
    }
    return excerpt(problem, kProblemLength);
}

// What nlohmann says of valid JSON it cannot hold, without its prefix
// ("[json.exception.out_of_range.406] "): e.g. "number overflow parsing '1e400'", whose quote of
// the number is cut to an excerpt.
std::string libraryProblem(const std::string& what) {
    const size_t prefixEnd = what.find("] ");
    const bool prefixed = what.starts_with("[json.exception.") && prefixEnd != std::string::npos;
    return excerpt(prefixed ? what.substr(prefixEnd + 2) : what, kProblemLength);
}

}  // namespace

std::string_view jsonText(const std::vector<char>& bytes, bool binary, const Report& report) {
    if (!binary) return {bytes.data(), bytes.size()};
    if (bytes.size() < 4 || std::memcmp(bytes.data(), "glTF", 4) != 0)
        report.fail("not a binary glTF file (bad magic: it does not start with \"glTF\")" + notGlbHint(bytes));
    if (bytes.size() < kGlbHeader + kChunkHeader)
        report.fail("truncated binary glTF: " + std::to_string(bytes.size()) + " bytes, too short for its JSON chunk");
    const uint32_t version = readU32(bytes, 4), length = readU32(bytes, 8);
    if (version != 2)
        report.fail("binary glTF container version " + std::to_string(version) + " is not supported (only 2)");
    if (length > bytes.size())
        report.fail("truncated binary glTF: its header gives " + std::to_string(length) + " bytes, the file has " +
                    std::to_string(bytes.size()));
    const uint32_t chunkLength = readU32(bytes, kGlbHeader), chunkType = readU32(bytes, kGlbHeader + 4);
    if (chunkType != kJsonChunk) report.fail("binary glTF: its first chunk is not of type JSON");
    if (uint64_t(kGlbHeader + kChunkHeader) + chunkLength > length)
        report.fail("truncated binary glTF: its JSON chunk of " + std::to_string(chunkLength) +
                    " bytes runs past the end (" + std::to_string(length) + " bytes)");
    return {bytes.data() + kGlbHeader + kChunkHeader, chunkLength};
}

nlohmann::json parseJson(std::string_view text, const Report& report) {
    try {
        return nlohmann::json::parse(text.begin(), text.end());
    } catch (const nlohmann::json::parse_error& e) {
        // e.byte counts from 1 and may point one past the end (the input ended too early).
        const size_t at = std::min(e.byte > 0 ? e.byte - 1 : 0, text.size());
        const std::string_view before = text.substr(0, at);
        const size_t line = 1 + size_t(std::count(before.begin(), before.end(), '\n'));
        const size_t lineStart = before.rfind('\n') == std::string_view::npos ? 0 : before.rfind('\n') + 1;
        const std::string problem = jsonProblem(e.what());
        report.fail("not valid JSON at line " + std::to_string(line) + ", column " +
                    std::to_string(at - lineStart + 1) + (problem.empty() ? "" : " (" + problem + ")"));
    } catch (const nlohmann::json::exception& e) {
        report.fail("cannot read its JSON (" + libraryProblem(e.what()) + ")");
    }
}

void checkNesting(const nlohmann::json& doc, const Report& report) {
    if (!doc.is_object()) return;  // checkAsset refuses it
    for (const auto& member : doc.items()) {
        // The member's values still to visit, each with its level.
        std::vector<std::pair<const nlohmann::json*, size_t>> pending{{&member.value(), 2}};
        while (!pending.empty()) {
            const auto [value, depth] = pending.back();
            pending.pop_back();
            if (!value->is_structured()) continue;
            if (depth > kMaxJsonDepth)
                report.fail("its JSON nests arrays and objects deeper than " + std::to_string(kMaxJsonDepth) +
                            " levels (in " + quoted(member.key()) + "); tripath reads at most " +
                            std::to_string(kMaxJsonDepth));
            for (const auto& child : *value) pending.emplace_back(&child, depth + 1);
        }
    }
}

void checkAsset(const nlohmann::json& doc, const Report& report) {
    if (!doc.is_object())
        report.fail(std::string("not a glTF file: its JSON is ") + doc.type_name() + ", not an object");
    const auto asset = doc.find("asset");
    if (asset == doc.end() || !asset->is_object())
        report.fail("not a glTF file: it has no \"asset\" object "
                    "(a glTF 2.0 file has \"asset\": {\"version\": \"2.0\"})");
    const auto version = asset->find("version");
    if (version == asset->end() || !version->is_string())
        report.fail("asset.version is missing or not a string (a glTF 2.0 file has \"version\": \"2.0\")");
    const std::string& text = version->get_ref<const std::string&>();
    const size_t dot = text.find('.');
    const auto digits = [](std::string_view s) {
        return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    if (dot == std::string::npos || !digits(std::string_view(text).substr(0, dot)) ||
        !digits(std::string_view(text).substr(dot + 1)))
        report.fail("asset.version " + quoted(text) + " is not of the form major.minor (a glTF 2.0 file has \"2.0\")");
    if (text.substr(0, dot) != "2")
        report.fail("glTF version " + quoted(text) + " is not supported (only 2.x)");
}

}  // namespace tripath::gltf
