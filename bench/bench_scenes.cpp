#include "bench_scenes.h"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>

#include "scenes/builtin_scenes.h"
#include "scenes/scene_source.h"

namespace tripath::bench {

namespace {

constexpr const char* kTessPrefix = "tessellated:";

struct Entry {
    std::unique_ptr<Scene> scene;
    BuildStats stats;
};

std::mutex gMutex;
std::map<std::string, Entry>& cache() {
    static std::map<std::string, Entry> entries;
    return entries;
}

bool resetPeakRss() {
    std::ofstream f("/proc/self/clear_refs");
    f << "5";
    f.flush();
    return static_cast<bool>(f);
}

bool isGltfFile(const std::string& key) {
    const std::string ext = std::filesystem::path(key).extension().string();
    return ext == ".gltf" || ext == ".glb";
}

SceneDesc describe(const std::string& key) {
    if (key.rfind(kTessPrefix, 0) == 0) return cornellTessellated(std::stoull(key.substr(std::strlen(kTessPrefix))));
    if (!isGltfFile(key)) return builtinScene(key);
    // Under a white sky, as `--environment 1,1,1` lights it: Khronos's sample models bring no light.
    SceneDesc desc = loadSceneDesc(key);
    desc.environment.width = desc.environment.height = 1;
    desc.environment.texels = {Spectrum(1.0f)};
    desc.environment.source = "1,1,1";
    return desc;
}

Entry& entryFor(const std::string& key) {
    std::lock_guard<std::mutex> lock(gMutex);
    auto it = cache().find(key);
    if (it != cache().end()) return it->second;
    Entry e;
    e.stats.peakWasReset = resetPeakRss();
    e.stats.rssBeforeKiB = procStatusKiB("VmRSS");
    const auto start = std::chrono::steady_clock::now();
    // The description is a temporary: only the Scene (triangles, materials, BVH) stays resident,
    // as in `tripath render`, which also drops its SceneDesc once the Scene exists.
    e.scene = std::make_unique<Scene>(describe(key), kWidth, kHeight);
    e.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    e.stats.rssAfterKiB = procStatusKiB("VmRSS");
    e.stats.peakKiB = procStatusKiB("VmHWM");
    e.stats.triangles = e.scene->triangles().size();
    return cache().emplace(key, std::move(e)).first->second;
}

}  // namespace

std::string tessellatedKey(size_t triangles) { return fmt::format("{}{}", kTessPrefix, triangles); }

const Scene& cachedScene(const std::string& key) { return *entryFor(key).scene; }
const BuildStats& buildStats(const std::string& key) { return entryFor(key).stats; }

long procStatusKiB(const char* field) {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return -1;
    char line[256];
    long value = -1;
    const size_t n = std::strlen(field);
    while (std::fgets(line, sizeof line, f))
        if (std::strncmp(line, field, n) == 0 && line[n] == ':') {
            value = std::strtol(line + n + 1, nullptr, 10);
            break;
        }
    std::fclose(f);
    return value;
}

tbb::task_arena& arenaFor(int threads) {
    // Arenas are created on first use and live for the process; std::map keeps references stable.
    static std::mutex m;
    static std::map<int, std::unique_ptr<tbb::task_arena>> arenas;
    std::lock_guard<std::mutex> lock(m);
    auto& a = arenas[threads];
    if (!a) a = std::make_unique<tbb::task_arena>(threads);
    return *a;
}

}  // namespace tripath::bench
