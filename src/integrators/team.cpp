#include "integrators/team.h"

#include "core/error.h"

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
    void broadcast(std::string&) override {}
    std::vector<std::string> gather(const std::string& mine) override { return {mine}; }
};
}  // namespace

Team& solo() {
    static Solo team;
    return team;
}

void together(Team& team, const std::function<void()>& step) {
    std::string error;
    try {
        step();
    } catch (const InputError& e) {
        error = e.what();
        if (error.empty()) error = "failed";
    }
    if (!team.any(!error.empty())) return;
    // Rank 0 learns every rank's verdict, picks the lowest failing rank's and tells everyone.
    std::string verdict;
    const std::vector<std::string> all = team.gather(error);
    for (size_t r = 0; r < all.size() && verdict.empty(); ++r)
        if (!all[r].empty()) verdict = r == 0 ? all[r] : "rank " + std::to_string(r) + ": " + all[r];
    team.broadcast(verdict);
    throw InputError(verdict);
}

}  // namespace tripath
