// What the report's benchmark parts share: their command-line options (--out DIR, --quick), the JSON
// file each part writes for samples/bench/report.py, and .npy arrays of the exact probes and query
// points (so that Python peers such as scipy time the very same points).
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace bench {

struct PartOptions {
    std::string out_dir;  // empty: print tables only, write no files
    bool quick = false;   // the smoke run's smaller sweep
};

// Reads --out DIR and --quick from a part's arguments (others are left to the part).
PartOptions part_options(int argc, char** argv);

// The machine and the run, recorded in every part's JSON: CPU name, hardware threads, 1-minute load.
nlohmann::json machine_json(bool quick);

// Writes dir/name through a temporary file and a rename; creates dir. Throws std::runtime_error.
void write_json_file(const std::string& dir, const std::string& name, const nlohmann::json& value);

// Writes a float32 array of rows x cols as a NumPy .npy file (format 1.0, little-endian, C order).
void write_npy_f32(const std::string& dir, const std::string& name, const float* data, size_t rows, size_t cols);

// Reads what write_npy_f32 wrote (float32, little-endian, C order, two dimensions) into out; returns
// false when the file is missing or is not such an array, or its columns are not `cols`.
bool read_npy_f32(const std::string& path, size_t cols, std::vector<float>* out);

}  // namespace bench
