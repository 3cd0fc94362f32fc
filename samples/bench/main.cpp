// tetprobe_bench [store|bake|all]: the store benchmark (this folder's bench_store.cpp) and the bake
// benchmark (bench_bake.cpp). Default: all. `methods` and `precision` (bench_methods.cpp,
// bench_precision.cpp) write JSON for the report: tetprobe_bench methods|precision [--out DIR] [--quick].
#include "bench.h"

#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
    const char* which = argc > 1 ? argv[1] : "all";
    if (!std::strcmp(which, "methods")) return run_methods_bench(argc, argv);
    if (!std::strcmp(which, "precision")) return run_precision_bench(argc, argv);
    const bool store = !std::strcmp(which, "store") || !std::strcmp(which, "all");
    const bool bake = !std::strcmp(which, "bake") || !std::strcmp(which, "all");
    if (!store && !bake) {
        std::fprintf(stderr, "usage: tetprobe_bench [store|bake|all|methods|precision]\n");
        return 2;
    }
    int status = 0;
    if (store) status |= run_store_bench(argc, argv);
    if (bake) status |= run_bake_bench(argc, argv);
    return status;
}
