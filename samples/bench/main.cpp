// tetprobe_bench [store|bake|all]: the store benchmark (this folder's bench_store.cpp) and the bake
// benchmark (bench_bake.cpp). Default: all.
#include "bench.h"

#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
    const char* which = argc > 1 ? argv[1] : "all";
    if (!std::strcmp(which, "leak")) return run_leak_bench(argc, argv);  // not part of "all": bench_leak.cpp
    const bool store = !std::strcmp(which, "store") || !std::strcmp(which, "all");
    const bool bake = !std::strcmp(which, "bake") || !std::strcmp(which, "all");
    if (!store && !bake) {
        std::fprintf(stderr, "usage: tetprobe_bench [store|bake|all]\n");
        return 2;
    }
    int status = 0;
    if (store) status |= run_store_bench(argc, argv);
    if (bake) status |= run_bake_bench(argc, argv);
    return status;
}
