// A team of ranks that are threads of this process (integrators/team.h), so that tests can run the
// render loop's multi-process logic -- block dealing, stop votes, sums, film reduction, gathered
// logs, bytes broadcast and gathered -- without mpirun. Each collective is a rendezvous: every
// rank adds its part to a shared accumulator under a lock, all wait, all read the result, all wait
// again before the next one.
#pragma once
#include <algorithm>
#include <barrier>
#include <cstdint>
#include <functional>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "integrators/film.h"
#include "integrators/team.h"

namespace tripath::test {

class ThreadTeam {
public:
    explicit ThreadTeam(int size) : size_(size), barrier_(size) {}

    // Runs body(team, rank) on `size` threads at once, one per rank, and waits for them all.
    void run(const std::function<void(Team&, int)>& body) {
        std::vector<Rank> ranks;
        ranks.reserve(size_t(size_));
        for (int r = 0; r < size_; ++r) ranks.emplace_back(*this, r);
        std::vector<std::jthread> threads;
        for (int r = 0; r < size_; ++r) threads.emplace_back([&, r] { body(ranks[size_t(r)], r); });
    }

private:
    class Rank final : public Team {
    public:
        Rank(ThreadTeam& team, int rank) : team_(team), rank_(rank) {}
        int rank() const override { return rank_; }
        int size() const override { return team_.size_; }
        bool any(bool local) override {
            uint64_t v = local ? 1 : 0;
            team_.collective(rank_, std::span(&v, 1), [](uint64_t& acc, uint64_t x) { acc |= x; });
            return v != 0;
        }
        void sum(std::span<uint64_t> values) override {
            team_.collective(rank_, values, [](uint64_t& acc, uint64_t x) { acc += x; });
        }
        void max(std::span<uint64_t> values) override {
            team_.collective(rank_, values, [](uint64_t& acc, uint64_t x) { acc = std::max(acc, x); });
        }
        void reduce(Film& film) override {
            {
                const std::lock_guard lock(team_.mutex_);
                if (rank_ != 0) team_.films_.push_back(&film);
            }
            team_.barrier_.arrive_and_wait();  // every film posted
            if (rank_ == 0)
                for (const Film* other : team_.films_) film.add(*other);
            team_.barrier_.arrive_and_wait();  // rank 0 has read them: the others may go on
            if (rank_ == 0) team_.films_.clear();
            team_.barrier_.arrive_and_wait();
        }
        void broadcast(std::string& bytes) override {
            if (rank_ == 0) team_.bytes_.assign(1, bytes);
            team_.barrier_.arrive_and_wait();  // rank 0 has posted
            bytes = team_.bytes_[0];
            team_.barrier_.arrive_and_wait();  // every rank has read it
        }
        std::vector<std::string> gather(const std::string& mine) override {
            if (rank_ == 0) team_.bytes_.assign(size_t(team_.size_), std::string());
            team_.barrier_.arrive_and_wait();  // the slots exist
            team_.bytes_[size_t(rank_)] = mine;  // each rank its own slot
            team_.barrier_.arrive_and_wait();  // every rank has posted
            std::vector<std::string> all = rank_ == 0 ? team_.bytes_ : std::vector<std::string>{};
            team_.barrier_.arrive_and_wait();  // rank 0 has read them
            return all;
        }

    private:
        ThreadTeam& team_;
        int rank_;
    };

    template <class Op>
    void collective(int rank, std::span<uint64_t> values, Op op) {
        {
            const std::lock_guard lock(mutex_);
            if (arrived_++ == 0) acc_.assign(values.begin(), values.end());
            else
                for (size_t i = 0; i < values.size(); ++i) op(acc_[i], values[i]);
        }
        barrier_.arrive_and_wait();  // every rank has added its part
        std::copy(acc_.begin(), acc_.end(), values.begin());
        barrier_.arrive_and_wait();  // every rank has read the result
        if (rank == 0) arrived_ = 0;  // all wait below before anyone starts the next collective
        barrier_.arrive_and_wait();
    }

    int size_;
    std::barrier<> barrier_;
    std::mutex mutex_;
    int arrived_ = 0;
    std::vector<uint64_t> acc_;
    std::vector<const Film*> films_;
    std::vector<std::string> bytes_;
};

}  // namespace tripath::test
