// JSON pieces shared by the methods and precision benchmarks (defined in bench_methods.cpp).
#pragma once

#include "method_scene.h"

#include <nlohmann/json.hpp>

#include <string>

namespace bench {

// The "bake" block: rays, bounces, seed and why they were chosen.
nlohmann::ordered_json method_bake_json(const MethodSettings& settings);

// Writes j to dir/name through a temporary file and a rename (never a half-written file); 0 on success.
int write_json(const std::string& dir, const char* name, const nlohmann::ordered_json& j);

}  // namespace bench
