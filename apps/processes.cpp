#include "processes.h"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <vector>

#include "geometry/embree_isa.h"
#include "core/error.h"
#include "integrators/film.h"

namespace tripath::app {

namespace {

bool launchedByMpi() {
    for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
        if (std::getenv(var)) return true;
    return false;
}

// Sums of 192-bit fixed-point values (exact_sum.h), three uint64 words each: the reduction of
// films. Integer addition, so the result does not depend on the reduction tree MPI picks.
void addFixed192(void* in, void* inout, int* len, MPI_Datatype*) {
    const auto* a = static_cast<const Fixed192*>(in);
    auto* b = static_cast<Fixed192*>(inout);
    for (int i = 0; i < *len; ++i) b[i] += a[i];
}

// MPI counts are ints: long messages go in pieces.
constexpr size_t kPieceBytes = size_t(1) << 30;
void sendBytes(const std::string& bytes, int to) {
    uint64_t n = bytes.size();
    MPI_Send(&n, 1, MPI_UINT64_T, to, 0, MPI_COMM_WORLD);
    for (size_t at = 0; at < bytes.size(); at += kPieceBytes)
        MPI_Send(bytes.data() + at, int(std::min(kPieceBytes, bytes.size() - at)), MPI_CHAR, to, 0, MPI_COMM_WORLD);
}
std::string receiveBytes(int from) {
    uint64_t n = 0;
    MPI_Recv(&n, 1, MPI_UINT64_T, from, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::string bytes(n, '\0');
    for (size_t at = 0; at < bytes.size(); at += kPieceBytes)
        MPI_Recv(bytes.data() + at, int(std::min(kPieceBytes, bytes.size() - at)), MPI_CHAR, from, 0, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
    return bytes;
}

class MpiTeam final : public Team {
public:
    MpiTeam() {
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
        MPI_Type_contiguous(3, MPI_UINT64_T, &fixedType_);
        MPI_Type_commit(&fixedType_);
        MPI_Op_create(addFixed192, 1, &addOp_);
    }
    ~MpiTeam() override {
        MPI_Op_free(&addOp_);
        MPI_Type_free(&fixedType_);
    }
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    bool any(bool local) override {
        int v = local, out = 0;
        MPI_Allreduce(&v, &out, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
        return out != 0;
    }
    void sum(std::span<uint64_t> values) override { allreduce(values, MPI_SUM); }
    void max(std::span<uint64_t> values) override { allreduce(values, MPI_MAX); }
    void reduce(Film& film) override {
        for (ExactSums* sums : film.totals()) {
            // In pieces, so that counts stay within int and the buffers MPI allocates stay small.
            constexpr size_t kPiece = size_t(1) << 20;
            std::span<uint64_t> words = sums->words();
            for (size_t at = 0; at < sums->size(); at += kPiece) {
                const int n = static_cast<int>(std::min(kPiece, sums->size() - at));
                uint64_t* p = words.data() + 3 * at;
                MPI_Reduce(rank_ == 0 ? MPI_IN_PLACE : p, p, n, fixedType_, addOp_, 0, MPI_COMM_WORLD);
            }
        }
    }

    void broadcast(std::string& bytes) override {
        uint64_t n = bytes.size();
        MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
        bytes.resize(n);
        for (size_t at = 0; at < bytes.size(); at += kPieceBytes)
            MPI_Bcast(bytes.data() + at, int(std::min(kPieceBytes, bytes.size() - at)), MPI_CHAR, 0, MPI_COMM_WORLD);
    }
    std::vector<std::string> gather(const std::string& mine) override {
        if (rank_ != 0) {
            sendBytes(mine, 0);
            return {};
        }
        std::vector<std::string> all{mine};
        for (int r = 1; r < size_; ++r) all.push_back(receiveBytes(r));
        return all;
    }

private:
    void allreduce(std::span<uint64_t> values, MPI_Op op) {
        MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_UINT64_T, op, MPI_COMM_WORLD);
    }
    int rank_ = 0, size_ = 1;
    MPI_Datatype fixedType_;
    MPI_Op addOp_;
};

std::unique_ptr<MpiTeam> gTeam;

// Every rank runs the narrowest of the ranks' best ISAs, so that their hits agree.
void pinEmbreeIsa() {
    int best = bestEmbreeIsaLevel(), common = best;
    MPI_Allreduce(&best, &common, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    useEmbreeIsa(common);
}

// Ranks other than 0 keep quiet: progress, summaries and warnings come from rank 0 alone.
void silence() {
    static std::ofstream null("/dev/null");
    std::cerr.rdbuf(null.rdbuf());
    std::cout.rdbuf(null.rdbuf());
}

}  // namespace

Processes::Processes(int& argc, char**& argv) {
    if (!launchedByMpi()) return;
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);  // only the main thread calls MPI
    gTeam = std::make_unique<MpiTeam>();
    pinEmbreeIsa();
    if (gTeam->rank() != 0) silence();
}

Processes::~Processes() {
    if (!gTeam) return;
    gTeam.reset();
    MPI_Finalize();
}

void Processes::fail(const std::string& message, int exitCode) {
    if (!gTeam || gTeam->size() == 1) return;
    std::fprintf(stderr, "error: rank %d: %s\n", gTeam->rank(), message.c_str());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, exitCode);
}

bool launched() { return gTeam != nullptr; }
Team& team() { return gTeam ? static_cast<Team&>(*gTeam) : solo(); }
bool isRankZero() { return team().rank() == 0; }

void together(const std::function<void()>& step) { tripath::together(team(), step); }

}  // namespace tripath::app
