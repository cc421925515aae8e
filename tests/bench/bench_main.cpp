// minecrappy-bench: Google Benchmark's command line, or the speed gate with --gate (speed_gate.h).
#include <cstring>

#include <benchmark/benchmark.h>

#include "speed_gate.h"

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--gate") == 0) return bench::runSpeedGate(argc, argv);
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
