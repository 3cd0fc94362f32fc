#pragma once
int run_store_bench(int argc, char** argv);
int run_bake_bench(int argc, char** argv);
int run_methods_bench(int argc, char** argv);
int run_precision_bench(int argc, char** argv);
int run_locate_bench(int argc, char** argv);
int run_probe_count_bench(int argc, char** argv);
int run_leak_bench(int argc, char** argv);
int run_levels_bench(int argc, char** argv);
