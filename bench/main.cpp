// tripath_bench's entry point: Google Benchmark's usual main, plus the machine's load average in
// the report's context -- other work on the machine is the main source of noise here, so every
// result file says how busy the machine was when it started.
#include <benchmark/benchmark.h>

#include <fstream>
#include <string>

int main(int argc, char** argv) {
    std::ifstream loadavg("/proc/loadavg");
    std::string line;
    if (std::getline(loadavg, line)) benchmark::AddCustomContext("loadavg_at_start", line);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
