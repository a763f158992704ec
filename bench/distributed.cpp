// What distributed rendering adds to every render: the exact film totals that make N processes
// give one process's bits.
//
//   film/end_block/<W>x<H>   folding one block of passes (its double sums) into the exact
//                            totals, 2 threads: once per kPassesPerBlock passes in every render;
//                            reported per pixel and against the time of those passes
//   film/add/<W>x<H>         adding one film's exact totals to another, 1 thread: the arithmetic
//                            of the reduction over ranks (MPI adds its transfer, measured by
//                            bench/mpi-scale.sh)
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include "integrators/film.h"
#include "integrators/render.h"

namespace tripath::bench {

namespace {

Film filledFilm(int width, int height) {
    Film film(width, height);
    for (int p = 0; p < width * height; ++p)
        film.add(p, Strategy{0, 2}, Spectrum{0.25f + p % 7, 1.0f / (1 + p % 13), 3e-9f * (p % 5)}, Spectrum{});
    return film;
}

void endBlock(benchmark::State& state) {
    const int width = int(state.range(0)), height = int(state.range(1));
    Film film = filledFilm(width, height);
    tbb::task_arena arena(2);
    for (auto _ : state) {
        state.PauseTiming();
        for (int p = 0; p < width * height; ++p) film.add(p, Strategy{0, 2}, Spectrum{0.5f, 0.25f, 1e-3f}, Spectrum{});
        state.ResumeTiming();
        arena.execute([&] { film.endBlock(); });
    }
    state.counters["ns/pixel"] = benchmark::Counter(double(width) * height * state.iterations(),
                                                   benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void addFilms(benchmark::State& state) {
    const int width = int(state.range(0)), height = int(state.range(1));
    Film a = filledFilm(width, height), b = filledFilm(width, height);
    a.endBlock();
    b.endBlock();
    for (auto _ : state) a.add(b);
    state.counters["ns/pixel"] = benchmark::Counter(double(width) * height * state.iterations(),
                                                   benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.SetBytesProcessed(int64_t(state.iterations()) * width * height * 3 * int64_t(sizeof(Fixed192)));
}

void sizes(benchmark::internal::Benchmark* b) {
    b->Args({512, 512})->Args({1920, 1080})->Args({4096, 4096})->Unit(benchmark::kMillisecond)->UseRealTime();
}

}  // namespace

BENCHMARK(endBlock)->Name("film/end_block")->Apply(sizes);
BENCHMARK(addFilms)->Name("film/add")->Apply(sizes);

}  // namespace tripath::bench
