// Reads probe positions and SH from CSV (x,y,z[,27 sh] per line) or JSON
// ({"probes": [[x,y,z], ...], "sh": [[27 floats], ...]}).
#include "cli.h"

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace cli {

namespace {

bool ends_with(const std::string& text, const std::string& suffix) {
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Splits a CSV line into numbers; returns false if a field is not a number.
bool parse_csv_line(const std::string& line, std::vector<float>& out) {
    out.clear();
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) {
        const size_t first = field.find_first_not_of(" \t\r");
        const size_t last = field.find_last_not_of(" \t\r");
        if (first == std::string::npos) return false;
        field = field.substr(first, last - first + 1);
        char* end = nullptr;
        const float value = std::strtof(field.c_str(), &end);
        if (*end != '\0') return false;
        out.push_back(value);
    }
    return true;
}

ProbeFile read_csv(std::istream& in, const std::string& path) {
    ProbeFile file;
    std::string line;
    std::vector<float> values;
    size_t line_number = 0;
    bool header_skipped = false;
    while (std::getline(in, line)) {
        ++line_number;
        if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#')
            continue;
        if (!parse_csv_line(line, values)) {
            if (file.positions.empty() && !header_skipped) {  // one header line is allowed
                header_skipped = true;
                continue;
            }
            throw Failure(path + ":" + std::to_string(line_number) + ": not a list of numbers");
        }
        if (values.size() != 3 && values.size() != 30)
            throw Failure(path + ":" + std::to_string(line_number) + ": expected 3 (x,y,z) or 30 (x,y,z + 27 SH) "
                          "values, got " + std::to_string(values.size()));
        const size_t width = values.size();
        if (!file.positions.empty() && (width == 30) != !file.sh.empty())
            throw Failure(path + ":" + std::to_string(line_number) + ": every line must have the same columns");
        file.positions.insert(file.positions.end(), values.begin(), values.begin() + 3);
        if (width == 30) file.sh.insert(file.sh.end(), values.begin() + 3, values.end());
    }
    return file;
}

ProbeFile read_json(std::istream& in, const std::string& path) {
    nlohmann::json document;
    try {
        in >> document;
    } catch (const nlohmann::json::exception& e) {
        throw Failure(path + ": invalid JSON: " + e.what());
    }
    ProbeFile file;
    if (!document.is_object() || !document.contains("probes") || !document["probes"].is_array())
        throw Failure(path + ": expected an object with a \"probes\" array of [x, y, z]");
    const auto& probes = document["probes"];
    for (size_t i = 0; i < probes.size(); ++i) {
        const auto& p = probes[i];
        if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() || !p[2].is_number())
            throw Failure(path + ": probes[" + std::to_string(i) + "] is not [x, y, z]");
        for (int k = 0; k < 3; ++k) file.positions.push_back(p[k].get<float>());
    }
    if (document.contains("sh")) {
        const auto& sh = document["sh"];
        if (!sh.is_array() || sh.size() != probes.size())
            throw Failure(path + ": \"sh\" must have one entry of 27 numbers per probe");
        for (size_t i = 0; i < sh.size(); ++i) {
            if (!sh[i].is_array() || sh[i].size() != TP_SH_FLOATS)
                throw Failure(path + ": sh[" + std::to_string(i) + "] must have 27 numbers");
            for (const auto& value : sh[i]) {
                if (!value.is_number()) throw Failure(path + ": sh[" + std::to_string(i) + "] holds a non-number");
                file.sh.push_back(value.get<float>());
            }
        }
    }
    return file;
}

}  // namespace

ProbeFile read_probe_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Failure("cannot read " + path);
    if (ends_with(path, ".json")) return read_json(in, path);
    if (ends_with(path, ".csv") || ends_with(path, ".txt")) return read_csv(in, path);
    throw Failure(path + ": unknown input type (use .csv or .json)");
}

}  // namespace cli
