// A test that runs commands through the shell in a fresh folder of its own (removed afterwards),
// with their stderr captured: the end-to-end tests of the built binary share it.
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tripath::test {

class ShellTest : public testing::Test {
protected:
    struct Outcome {
        int exitCode;
        std::string err;
    };

    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("tripath-" + std::to_string(getpid()) + "-" + testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    // Runs `cmd` with stdout discarded; its exit code (-1 if it did not exit) and stderr.
    Outcome shell(const std::string& cmd) const {
        const std::string err = path("stderr.txt");
        const int status = std::system((cmd + " > /dev/null 2> '" + err + "'").c_str());
        std::ifstream in(err);
        std::stringstream s;
        s << in.rdbuf();
        return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, s.str()};
    }

    std::filesystem::path dir_;
};

}  // namespace tripath::test
