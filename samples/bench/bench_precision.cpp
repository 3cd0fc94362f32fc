int run_precision_bench(int, char**) { return 1; }
