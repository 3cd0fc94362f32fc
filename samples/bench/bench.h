#pragma once
int run_store_bench(int argc, char** argv);
int run_bake_bench(int argc, char** argv);
int run_leak_bench(int argc, char** argv);
