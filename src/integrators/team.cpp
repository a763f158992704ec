#include "integrators/team.h"

namespace tripath {

namespace {
class Solo final : public Team {
public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    bool any(bool local) override { return local; }
    void sum(std::span<uint64_t>) override {}
    void max(std::span<uint64_t>) override {}
    void reduce(Film&) override {}
};
}  // namespace

Team& solo() {
    static Solo team;
    return team;
}

}  // namespace tripath
