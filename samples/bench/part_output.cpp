#include "part_output.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

namespace bench {

namespace fs = std::filesystem;

PartOptions part_options(int argc, char** argv) {
    PartOptions options;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--quick")) options.quick = true;
        else if (!std::strcmp(argv[i], "--out") && i + 1 < argc) options.out_dir = argv[++i];
    }
    return options;
}

nlohmann::json machine_json(bool quick) {
    std::string cpu = "unknown CPU", load = "unknown", line;
    std::ifstream cpuinfo("/proc/cpuinfo");
    while (std::getline(cpuinfo, line))
        if (line.rfind("model name", 0) == 0) {
            cpu = line.substr(line.find(':') + 2);
            break;
        }
    std::ifstream("/proc/loadavg") >> load;
    return {{"cpu", cpu}, {"threads", std::thread::hardware_concurrency()}, {"load_average", load}, {"quick", quick}};
}

namespace {

// Writes bytes to dir/name atomically: a reader never sees a half-written file.
void write_atomically(const std::string& dir, const std::string& name, const std::string& bytes) {
    fs::create_directories(dir);
    const fs::path target = fs::path(dir) / name, temporary = fs::path(dir) / (name + ".tmp");
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), std::streamsize(bytes.size()));
        if (!out) throw std::runtime_error("cannot write " + temporary.string());
    }
    fs::rename(temporary, target);
}

}  // namespace

void write_json_file(const std::string& dir, const std::string& name, const nlohmann::json& value) {
    write_atomically(dir, name, value.dump(1) + "\n");
}

void write_npy_f32(const std::string& dir, const std::string& name, const float* data, size_t rows, size_t cols) {
    std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", " +
                         std::to_string(cols) + "), }";
    // Magic (6) + version (2) + length (2) + header, padded with spaces and a newline to 64 bytes.
    const size_t unpadded = 10 + header.size() + 1;
    header.append((64 - unpadded % 64) % 64, ' ');
    header += '\n';
    std::string bytes = "\x93NUMPY";
    bytes += char(1);
    bytes += char(0);
    bytes += char(header.size() & 255);
    bytes += char(header.size() >> 8);
    bytes += header;
    // Little-endian float32 is the in-memory layout on every platform this benchmark builds for.
    bytes.append(reinterpret_cast<const char*>(data), rows * cols * sizeof(float));
    write_atomically(dir, name, bytes);
}

bool read_npy_f32(const std::string& path, size_t cols, std::vector<float>* out) {
    std::ifstream in(path, std::ios::binary);
    char start[10];
    if (!in.read(start, sizeof start) || std::memcmp(start, "\x93NUMPY\x01\x00", 8) != 0) return false;
    const size_t header_size = size_t(uint8_t(start[8])) | size_t(uint8_t(start[9])) << 8;
    std::string header(header_size, ' ');
    if (!in.read(&header[0], std::streamsize(header_size))) return false;
    const std::string descr = "'descr': '<f4', 'fortran_order': False, 'shape': (";
    const size_t at = header.find(descr);
    if (at == std::string::npos) return false;
    size_t rows = 0, columns = 0;
    if (std::sscanf(header.c_str() + at + descr.size(), "%zu, %zu)", &rows, &columns) != 2 || columns != cols) return false;
    out->assign(rows * cols, 0.0f);
    return bool(in.read(reinterpret_cast<char*>(out->data()), std::streamsize(out->size() * sizeof(float))));
}

}  // namespace bench
