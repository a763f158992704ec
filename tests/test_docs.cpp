// The documentation against the binary: every flag's help lives once, in the code, and the pages
// in docs/ are made from it or checked against it here, so that a flag added, renamed or dropped
// cannot leave the docs behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace tripath {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = TRIPATH_SOURCE_DIR;

std::string readFile(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Every "--flag" in the text (not "---" rules, not part of a word: not --gtest_filter's "--gtest").
std::set<std::string> flagsIn(const std::string& text) {
    static const std::regex flag("(^|[^A-Za-z0-9_-])(--[a-z][a-z0-9-]*)(?![A-Za-z0-9_])");
    std::set<std::string> found;
    for (auto i = std::sregex_iterator(text.begin(), text.end(), flag); i != std::sregex_iterator(); ++i)
        found.insert((*i)[2]);
    return found;
}

// README.md and docs/*.md but the generated reference.
std::string prose() {
    std::string text = readFile(kSource / "README.md");
    for (const auto& entry : fs::directory_iterator(kSource / "docs"))
        if (entry.path().extension() == ".md" && entry.path().filename() != "flags.md") text += readFile(entry.path());
    return text;
}

// docs/flags.md is what scripts/flags-reference.sh makes of this binary's --help, byte for byte.
// Catches a flag added, dropped or re-described in the code without the reference made again.
TEST(Docs, FlagReferenceIsTheHelp) {
    const fs::path made = fs::temp_directory_path() / ("tripath-flags-" + std::to_string(getpid()) + ".md");
    const std::string command = "bash '" + (kSource / "scripts/flags-reference.sh").string() + "' '" TRIPATH_BINARY "' > '" +
                                made.string() + "'";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    std::istringstream now(readFile(made)), page(readFile(kSource / "docs/flags.md"));
    fs::remove(made);
    for (int line = 1;; ++line) {
        std::string a, b;
        const bool inMade = bool(std::getline(now, a)), inPage = bool(std::getline(page, b));
        if (!inMade && !inPage) break;
        ASSERT_EQ(inPage ? b : "(end of file)", inMade ? a : "(end of file)")
            << "docs/flags.md line " << line << " is stale: bash scripts/flags-reference.sh build/tripath > docs/flags.md";
    }
}

// Every flag of every command is explained in the prose (README.md or a page of docs/), and every
// flag the prose names is one of tripath's, or of the other programs it shows being run. Catches
// a new flag documented only by its --help, and a page still naming a flag that was renamed.
TEST(Docs, ProseNamesEveryFlagAndNoOther) {
    const std::set<std::string> help = flagsIn(readFile(kSource / "docs/flags.md")), named = flagsIn(prose());
    ASSERT_GT(help.size(), 40u) << "docs/flags.md lists too few flags to be the reference";
    for (const std::string& f : help)
        if (f != "--help" && f != "--version") EXPECT_TRUE(named.count(f)) << f << " is in --help but in no page of docs/";
    // mpirun's and srun's, CMake's, pip's and venv's, Embree's tutorial's, and those of the scripts
    // measuring tripath against Cycles (scripts/cycles-compare.sh, cycles-compare.py, cycles-render.py).
    const std::set<std::string> others{"--allow-run-as-root", "--bind-to", "--cpus-per-task", "--hostfile", "--map-by",
                                       "--mpi", "--ntasks-per-node", "--install", "--prefix", "--system-site-packages",
                                       "--benchmark", "--cycles", "--cycles-only", "--flat", "--lambert", "--no-terminator-offset",
                                       "--tripath"};
    for (const std::string& f : named)
        EXPECT_TRUE(help.count(f) || others.count(f)) << f << " is named in the docs but is no flag of tripath's";
}

}  // namespace
}  // namespace tripath
