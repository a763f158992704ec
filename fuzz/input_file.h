// A fuzz input as a file: the readers under fuzzing take a path, so each input's bytes are written
// to a file named as the target asks (the name's extension picks an image reader). Each process
// gets its own empty folder, so relative URIs in an input find nothing but the input itself; it is
// removed when the process ends normally (the test suite's runs; libFuzzer's rarely do).
#pragma once
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

namespace tripath::fuzz {

class InputFolder {
public:
    InputFolder() : dir_(std::filesystem::temp_directory_path() / ("tripath-fuzz-" + std::to_string(getpid()))) {
        std::filesystem::create_directories(dir_);
    }
    ~InputFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(dir_, ignored);
    }
    InputFolder(const InputFolder&) = delete;
    InputFolder& operator=(const InputFolder&) = delete;
    std::filesystem::path file(const std::string& name) const { return dir_ / name; }

private:
    std::filesystem::path dir_;
};

// `bytes` written to the file `name` in this process's folder; its path.
inline std::string writeInput(const std::string& name, std::string_view bytes) {
    static const InputFolder folder;
    const std::string path = folder.file(name).string();
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw std::runtime_error("cannot write the input to " + path);
    if (!bytes.empty()) std::fwrite(bytes.data(), 1, bytes.size(), f);
    std::fclose(f);
    return path;
}

}  // namespace tripath::fuzz
