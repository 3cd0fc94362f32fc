// Shared pieces of the `tetprobe` command: errors, owning handles over the C ABI, small helpers.
// The command uses the library through capi/tetprobe.h only.
#pragma once

#include "tetprobe.h"

#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace cli {

// A failure the command reports as "tetprobe: error: <message>" with exit status 1.
struct Failure : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A wrong command line: reported with the usage text and exit status 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Throws Failure naming the call and carrying the library's message unless status is TP_OK.
void check(tp_status status, const char* call);

struct StoreRelease {
    void operator()(tp_store* store) const { tp_store_release(store); }
};
struct SceneRelease {
    void operator()(tp_scene* scene) const { tp_scene_release(scene); }
};
using StorePtr = std::unique_ptr<tp_store, StoreRelease>;
using ScenePtr = std::unique_ptr<tp_scene, SceneRelease>;

StorePtr load_store(const std::string& path);
// How a store is built beyond its probes: TP_BUILD_* flags and tp_build_options' format-5 choices.
struct BuildChoices {
    uint32_t flags = 0;
    uint32_t sh_encoding = TP_SH_ENCODING_HALF;
    bool quantize_positions = false;
    uint32_t layout = TP_LAYOUT_FAST;
};
// scene: leak control (tp_build_options.scene), or NULL.
StorePtr build_store(const std::vector<float>& positions, const std::vector<float>& sh, bool show_progress,
                     const BuildChoices& choices = BuildChoices(), const tp_scene* scene = nullptr);
// "fast", "compact" or "rebuilt": the layout of a store's blob (tp_store_info.layout).
const char* store_layout(const tp_store_info& info);
// "half", "unorm8", "half_l1" or "unorm8_l1" (tp_store_info.sh_encoding); and back (false if unknown).
const char* sh_encoding_name(uint32_t encoding);
bool sh_encoding_from_name(const std::string& name, uint32_t* encoding);
// The names of tp_store_info.section_bytes' entries, by TP_STORE_SECTION_*.
extern const char* const kStoreSectionNames[TP_STORE_SECTION_COUNT];
tp_store_info store_info(const tp_store* store);

// Probe positions (3 per probe) and SH (27 per probe, or empty) read from a CSV or JSON file.
struct ProbeFile {
    std::vector<float> positions;
    std::vector<float> sh;
};
ProbeFile read_probe_file(const std::string& path);

// Writes a probe file (docs/probe-file.md): x,y,z and, when sh is not empty, its 27 coefficients per
// line, every float printed so that it reads back to the same bits.
void write_probe_file(const std::string& path, const std::vector<float>& positions, const std::vector<float>& sh);

// Writes bytes to path atomically: a temporary file beside it, then a rename.
void write_file_atomically(const std::string& path, const void* data, size_t size);

// An RGB image of width x height floats (linear), written as an 8-bit PNG through stb_image_write.
struct Image {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
};
// Colour ramps: heat (dark blue -> red -> yellow -> white) for values, diverging (blue -> white -> red) for
// differences around 0.
enum class Ramp { heat, diverging };
// Maps values to a ramp over [lo, hi].
Image colour_map(const std::vector<float>& values, int width, int height, float lo, float hi, Ramp ramp = Ramp::heat);
void mark(Image& image, int x, int y, const unsigned char colour[3], int radius);
void write_png(const std::string& path, const Image& image);

// Text in a 5x7 bitmap font (bitmap_font.cpp), each font pixel a scale x scale square; (x, y) is the
// top left corner.
constexpr int kGlyphWidth = 5, kGlyphHeight = 7;
int text_width(const std::string& text, int scale);
void draw_text(Image& image, int x, int y, const std::string& text, int scale, const unsigned char colour[3]);

// World ranges of a slice picture: its columns span x, its rows z (row 0 at z_lo, at the top).
struct SliceAxes {
    float x_lo, x_hi, z_lo, z_hi;
};

// A colour bar drawn right after panel `after_panel`: the ramp over [lo, hi] with ticks and a label.
struct ColourBar {
    size_t after_panel;
    float lo, hi;
    std::string label;
    Ramp ramp = Ramp::heat;
};

// Panels of one size side by side on a white canvas (figure.cpp), each with its title, ticks in metres
// and the labels "x (m)" and "z (m)", and colour bars among them (each after the panels it scales), then
// an optional caption line below: a picture that says what its colours and distances mean.
Image framed_figure(const std::vector<Image>& panels, const std::vector<std::string>& titles, const SliceAxes& axes,
                    const std::vector<ColourBar>& bars, const std::string& caption = "");
// The common case: one colour bar after the last panel.
Image framed_figure(const std::vector<Image>& panels, const std::vector<std::string>& titles, const SliceAxes& axes,
                    float value_lo, float value_hi, const std::string& value_label);

// Progress bar on stderr; a tp_progress_fn (user = ProgressBar*).
struct ProgressBar {
    std::string label;
    int last_percent = -1;
    static int callback(void* user, float fraction, const char* stage);
    void finish();
};

// A command's arguments: positionals, options with a value ("-o FILE") and flags ("--json").
struct Arguments {
    std::vector<std::string> positional;
    std::map<std::string, std::string> values;
    std::set<std::string> flags;
    bool has(const std::string& name) const { return values.count(name) || flags.count(name); }
    std::string value(const std::string& name, const std::string& fallback) const {
        auto it = values.find(name);
        return it == values.end() ? fallback : it->second;
    }
};
Arguments parse_arguments(const std::vector<std::string>& args, const std::set<std::string>& value_options,
                          const std::set<std::string>& flag_options);

// The scene at path (glTF, FBX, OBJ or JSON) loaded with the options --scale and --up of a (kSceneOptions);
// the import's notes go to stderr.
const std::set<std::string> kSceneOptions = {"--scale", "--up"};
ScenePtr load_scene(const std::string& path, const Arguments& a);
// value_options with kSceneOptions added.
std::set<std::string> with_scene_options(std::set<std::string> value_options);

// The lighting bake of a scene's probes with a progress bar, shared by `bake` and `demo`.
struct BakeSettings {
    uint32_t rays = 256;
    uint32_t bounces = 2;
    uint64_t seed = 0;
    uint32_t threads = 0;
};
struct BakeResult {
    std::vector<float> positions;  // 3 per probe
    std::vector<float> sh;         // 27 per probe
    tp_effects_plan plan;
    std::string plan_text;
    double seconds = 0;
};
BakeSettings bake_settings(const Arguments& a, uint32_t default_rays);
// positions: 3 per probe, or empty for the scene's own probes.
BakeResult bake_scene(const tp_scene* scene, const BakeSettings& settings, const std::vector<float>& positions = {});

// Replaces a scene's probes with automatically placed ones (tp_place_probes at `spacing`, chosen
// until the estimated error is at most `error_bound`) and prints what placement did; the demo's scene uses it.
void place_scene_probes(tp_scene* scene, float spacing, float error_bound);

// Command-line parsing helpers.
double parse_number(const std::string& text, const char* what);
unsigned long parse_count(const std::string& text, const char* what);

int command_build(const std::vector<std::string>& args);
int command_info(const std::vector<std::string>& args);
int command_query(const std::vector<std::string>& args);
int command_bake(const std::vector<std::string>& args);
int command_plan(const std::vector<std::string>& args);
int command_demo(const std::vector<std::string>& args);
int command_place(const std::vector<std::string>& args);

}  // namespace cli
