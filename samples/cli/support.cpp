// Helpers shared by the commands: status checks, owning handles, atomic files, progress, parsing.
#include "cli.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <unistd.h>

namespace cli {

void check(tp_status status, const char* call) {
    if (status == TP_OK) return;
    throw Failure(std::string(call) + " failed: " + tp_status_name(status) + ": " + tp_last_error());
}

StorePtr load_store(const std::string& path) {
    tp_store* store = nullptr;
    check(tp_store_load_file(path.c_str(), &store), "loading the store");
    return StorePtr(store);
}

StorePtr build_store(const std::vector<float>& positions, const std::vector<float>& sh, bool show_progress,
                     uint32_t flags, const tp_scene* scene) {
    tp_build_options options;
    check(tp_build_options_init(&options), "tp_build_options_init");
    options.flags |= flags;
    options.scene = scene;
    ProgressBar bar{"build"};
    if (show_progress) {
        options.progress = &ProgressBar::callback;
        options.progress_user = &bar;
    }
    tp_store* store = nullptr;
    const size_t count = positions.size() / 3;
    tp_status status = tp_store_build(positions.data(), 0, sh.empty() ? nullptr : sh.data(), 0, count, &options, &store);
    if (show_progress) bar.finish();
    check(status, "building the store");
    return StorePtr(store);
}

tp_store_info store_info(const tp_store* store) {
    tp_store_info info;
    std::memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    check(tp_store_get_info(store, &info), "tp_store_get_info");
    return info;
}

const char* store_layout(const tp_store_info& info) { return (info.flags & TP_BUILD_COMPACT) ? "compact" : "fast"; }

void write_file_atomically(const std::string& path, const void* data, size_t size) {
    const std::string temporary = path + ".tmp" + std::to_string(static_cast<long>(getpid()));
    FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file) throw Failure("cannot write " + path + ": " + std::strerror(errno));
    bool ok = std::fwrite(data, 1, size, file) == size;
    ok = (std::fflush(file) == 0) && ok;
    ok = (fsync(fileno(file)) == 0) && ok;
    ok = (std::fclose(file) == 0) && ok;
    if (!ok || std::rename(temporary.c_str(), path.c_str()) != 0) {
        const std::string reason = std::strerror(errno);
        std::remove(temporary.c_str());
        throw Failure("cannot write " + path + ": " + reason);
    }
}

int ProgressBar::callback(void* user, float fraction, const char* stage) {
    auto* bar = static_cast<ProgressBar*>(user);
    const int percent = static_cast<int>(std::lround(std::fmin(std::fmax(fraction, 0.0f), 1.0f) * 100.0f));
    if (percent == bar->last_percent) return 0;
    // On a terminal the bar redraws in place; in a log (CI, pipes) only every 25% gets a line.
    static const bool interactive = isatty(fileno(stderr));
    if (!interactive) {
        if (bar->last_percent >= 0 && percent / 25 == bar->last_percent / 25) return 0;
        bar->last_percent = percent;
        std::fprintf(stderr, "%-6s %3d%% %s\n", bar->label.c_str(), percent, stage ? stage : "");
        return 0;
    }
    bar->last_percent = percent;
    const int filled = percent * 30 / 100;
    std::fprintf(stderr, "\r%-6s [%.*s%*s] %3d%% %-24.24s", bar->label.c_str(), filled,
                 "##############################", 30 - filled, "", percent, stage ? stage : "");
    std::fflush(stderr);
    return 0;
}

void ProgressBar::finish() {
    if (last_percent >= 0 && isatty(fileno(stderr))) std::fputc('\n', stderr);
    last_percent = -1;
}

Arguments parse_arguments(const std::vector<std::string>& args, const std::set<std::string>& value_options,
                          const std::set<std::string>& flag_options) {
    Arguments out;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        const bool looks_like_option = arg.size() > 1 && arg[0] == '-' && !(arg[1] >= '0' && arg[1] <= '9') && arg[1] != '.';
        if (!looks_like_option) {
            out.positional.push_back(arg);
        } else if (value_options.count(arg)) {
            if (i + 1 >= args.size()) throw UsageError(arg + " needs a value");
            out.values[arg] = args[++i];
        } else if (flag_options.count(arg)) {
            out.flags.insert(arg);
        } else {
            throw UsageError("unknown option " + arg);
        }
    }
    return out;
}

double parse_number(const std::string& text, const char* what) {
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(value))
        throw UsageError(std::string(what) + " must be a finite number (got \"" + text + "\")");
    return value;
}

unsigned long parse_count(const std::string& text, const char* what) {
    char* end = nullptr;
    errno = 0;
    const unsigned long value = std::strtoul(text.c_str(), &end, 10);
    if (text.empty() || text[0] == '-' || *end != '\0' || errno == ERANGE)
        throw UsageError(std::string(what) + " must be a non-negative integer (got \"" + text + "\")");
    return value;
}

}  // namespace cli
