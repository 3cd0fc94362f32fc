// Which way is up in a scene (one of the six axis directions), and the exact turns between such
// frames: a proper rotation that maps one axis direction onto another permutes coordinates and flips
// signs, so turning a float position there and back gives the very same bits.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace tetprobe {

// The values are the C ABI's TP_UP_*. `file` means "what the file says" and is only ever an option.
enum class UpAxis : uint32_t { file = 0, pos_x = 1, neg_x = 2, pos_y = 3, neg_y = 4, pos_z = 5, neg_z = 6 };

// "+y", "-z", ...; throws Error(Status::scene) naming `where` for anything else.
UpAxis parse_up_axis(const std::string& text, const std::string& where);
std::string up_axis_name(UpAxis up);  // "+y"
bool is_axis(UpAxis up);              // one of the six directions (not `file`, not out of range)
// The axis (0, 1, 2) and the sign (+1, -1) of an up direction (is_axis must hold).
int up_axis_index(UpAxis up);
int up_axis_sign(UpAxis up);

// A rotation that permutes axes and flips signs: out[i] = sign[i] * in[from[i]], with determinant +1.
struct AxisTurn {
    std::array<int, 3> from{{0, 1, 2}};
    std::array<int, 3> sign{{1, 1, 1}};

    bool identity() const { return from == std::array<int, 3>{{0, 1, 2}} && sign == std::array<int, 3>{{1, 1, 1}}; }
    template <typename T>
    void apply(const T in[3], T out[3]) const {
        const T copy[3] = {in[0], in[1], in[2]};
        for (int i = 0; i < 3; ++i) out[i] = sign[i] > 0 ? copy[from[i]] : -copy[from[i]];
    }
    AxisTurn inverse() const;
    UpAxis apply(UpAxis up) const;
};

// The turn that takes the direction `from` onto `to` (both axes): the identity when they are equal,
// a quarter turn when they are perpendicular, a half turn about the lowest remaining axis when they
// are opposite.
AxisTurn turn_between(UpAxis from, UpAxis to);

}  // namespace tetprobe
