// tetprobe_bench [store|bake|locate|probes|all|methods|precision|leak|levels] [--out DIR] [--quick]: the store
// benchmark (this folder's bench_store.cpp; `store --queries` and `store --workers` are its quick query and
// persistent-worker parts) and the bake benchmark (bench_bake.cpp), and the parts of
// the report that write JSON into DIR for samples/bench/report.py: methods and precision
// (bench_methods.cpp, bench_precision.cpp), locate and probes (bench_locate.cpp,
// bench_probe_count.cpp), leak (bench_leak.cpp) and the real levels (bench_levels.cpp); bake writes bake.json too
// when given --out. Default: all (store, bake,
// locate, probes).
#include "bench.h"

#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
    const char* which = argc > 1 ? argv[1] : "all";
    if (!std::strcmp(which, "methods")) return run_methods_bench(argc, argv);
    if (!std::strcmp(which, "precision")) return run_precision_bench(argc, argv);
    if (!std::strcmp(which, "levels")) return run_levels_bench(argc, argv);  // bench_levels.cpp
    if (!std::strcmp(which, "leak")) return run_leak_bench(argc, argv);  // not part of "all": bench_leak.cpp
    const bool all = !std::strcmp(which, "all");
    const bool store = all || !std::strcmp(which, "store");
    const bool bake = all || !std::strcmp(which, "bake");
    const bool locate = all || !std::strcmp(which, "locate");
    const bool probes = all || !std::strcmp(which, "probes");
    if (!store && !bake && !locate && !probes) {
        std::fprintf(stderr, "usage: tetprobe_bench [store|bake|locate|probes|all|methods|precision|leak|levels] [--out DIR] "
                             "[--quick]\n       tetprobe_bench store --queries | --workers   (quick parts of the store benchmark)\n");
        return 2;
    }
    int status = 0;
    if (store) status |= run_store_bench(argc, argv);
    if (bake) status |= run_bake_bench(argc, argv);
    if (locate) status |= run_locate_bench(argc, argv);
    if (probes) status |= run_probe_count_bench(argc, argv);
    return status;
}
