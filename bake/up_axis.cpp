#include "bake/up_axis.h"

#include "core/error.h"

namespace tetprobe {

namespace {

const char* const kNames[7] = {"file", "+x", "-x", "+y", "-y", "+z", "-z"};

UpAxis axis_of(int index, int sign) { return UpAxis(1 + 2 * index + (sign < 0 ? 1 : 0)); }

}  // namespace

bool is_axis(UpAxis up) { return uint32_t(up) >= 1 && uint32_t(up) <= 6; }

int up_axis_index(UpAxis up) { return int(uint32_t(up) - 1) / 2; }

int up_axis_sign(UpAxis up) { return (uint32_t(up) - 1) % 2 == 0 ? 1 : -1; }

UpAxis parse_up_axis(const std::string& text, const std::string& where) {
    for (uint32_t i = 1; i <= 6; ++i)
        if (text == kNames[i]) return UpAxis(i);
    throw Error(Status::scene, where + ": up is \"" + text + "\", not one of +x, -x, +y, -y, +z, -z");
}

std::string up_axis_name(UpAxis up) { return uint32_t(up) <= 6 ? kNames[uint32_t(up)] : "unknown"; }

AxisTurn AxisTurn::inverse() const {
    AxisTurn back;
    for (int i = 0; i < 3; ++i) {
        back.from[from[i]] = i;
        back.sign[from[i]] = sign[i];
    }
    return back;
}

UpAxis AxisTurn::apply(UpAxis up) const {
    int v[3] = {0, 0, 0}, out[3];
    v[up_axis_index(up)] = up_axis_sign(up);
    apply(v, out);
    for (int i = 0; i < 3; ++i)
        if (out[i] != 0) return axis_of(i, out[i]);
    return up;  // not reached: a turn maps an axis onto an axis
}

AxisTurn turn_between(UpAxis from, UpAxis to) {
    if (!is_axis(from) || !is_axis(to))
        throw Error(Status::invalid_argument, "turn_between needs two axis directions");
    const int a = up_axis_index(from), b = up_axis_index(to);
    const int sa = up_axis_sign(from), sb = up_axis_sign(to);
    AxisTurn turn;
    if (a == b) {
        if (sa == sb) return turn;
        // A half turn about the lowest other axis c: the two axes other than c flip.
        const int c = a == 0 ? 1 : 0;
        for (int i = 0; i < 3; ++i) turn.sign[i] = i == c ? 1 : -1;
        return turn;
    }
    // A quarter turn about the third axis c: out[b] = (sb * sa) * in[a], out[a] = s * in[b], out[c] = in[c],
    // where s makes the determinant +1.
    const int c = 3 - a - b;
    turn.from[b] = a;
    turn.sign[b] = sa * sb;
    turn.from[a] = b;
    turn.from[c] = c;
    turn.sign[c] = 1;
    // The permutation (a b) alone has determinant -1 times the product of the signs; choose sign[a] so
    // that the whole is +1.
    turn.sign[a] = -turn.sign[b];
    return turn;
}

}  // namespace tetprobe
