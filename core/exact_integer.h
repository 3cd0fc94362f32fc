// Exact signed integers of fixed capacity, for the exact fallback of the in-sphere predicates: a float
// is an integer times a power of two, so after scaling a handful of float coordinates by their common
// power of two a determinant of them is an integer polynomial, evaluated here without any rounding.
// Sign and magnitude, 32-bit limbs (least significant first), no allocation.
#pragma once

#include <cstdint>

namespace tetprobe {

struct ExactInteger {
    // 1,536 bits: float coordinates scaled to integers are below 2^277 (2^128 over the smallest
    // denormal's 2^-149); a degree-5 determinant of their differences stays below 2^1400, and no
    // product below takes more limbs than its factors together (at most 45 here).
    static constexpr int kCapacity = 48;
    uint32_t limb[kCapacity];
    int size = 0;           // limbs in use; limb[size - 1] != 0, or size 0 for zero
    bool negative = false;  // never set for zero

    int sign() const { return size == 0 ? 0 : negative ? -1 : 1; }
};

// magnitude * 2^shift, negated when negative; shift + 32 <= 32 * kCapacity.
inline void exact_scaled(uint32_t magnitude, int shift, bool negative, ExactInteger& out) {
    out.size = 0;
    out.negative = false;
    if (magnitude == 0) return;
    const int whole = shift / 32, part = shift % 32;
    for (int i = 0; i < whole; ++i) out.limb[i] = 0;
    const uint64_t shifted = uint64_t(magnitude) << part;
    out.limb[whole] = uint32_t(shifted);
    out.limb[whole + 1] = uint32_t(shifted >> 32);
    out.size = out.limb[whole + 1] != 0 ? whole + 2 : whole + 1;
    out.negative = negative;
}

namespace exact_detail {

inline int compare_magnitudes(const ExactInteger& a, const ExactInteger& b) {
    if (a.size != b.size) return a.size < b.size ? -1 : 1;
    for (int i = a.size - 1; i >= 0; --i)
        if (a.limb[i] != b.limb[i]) return a.limb[i] < b.limb[i] ? -1 : 1;
    return 0;
}

// out = |a| + |b| (out may be a or b).
inline void add_magnitudes(const ExactInteger& a, const ExactInteger& b, ExactInteger& out) {
    const ExactInteger& longer = a.size >= b.size ? a : b;
    const ExactInteger& shorter = a.size >= b.size ? b : a;
    const int n = longer.size, m = shorter.size;
    uint64_t carry = 0;
    for (int i = 0; i < n; ++i) {
        const uint64_t sum = uint64_t(longer.limb[i]) + (i < m ? shorter.limb[i] : 0u) + carry;
        out.limb[i] = uint32_t(sum);
        carry = sum >> 32;
    }
    out.size = n;
    if (carry != 0) out.limb[out.size++] = uint32_t(carry);
}

// out = |a| - |b| for |a| >= |b| (out may be a or b).
inline void subtract_magnitudes(const ExactInteger& a, const ExactInteger& b, ExactInteger& out) {
    const int n = a.size, m = b.size;
    int64_t borrow = 0;
    for (int i = 0; i < n; ++i) {
        int64_t difference = int64_t(a.limb[i]) - (i < m ? int64_t(b.limb[i]) : 0) - borrow;
        borrow = difference < 0;
        if (difference < 0) difference += int64_t(1) << 32;
        out.limb[i] = uint32_t(difference);
    }
    int size = n;
    while (size > 0 && out.limb[size - 1] == 0) --size;
    out.size = size;
}

// out = a + (b_negative ? -|b| : |b|).
inline void add_signed(const ExactInteger& a, const ExactInteger& b, bool b_negative, ExactInteger& out) {
    if (b.size == 0) {
        out = a;
        return;
    }
    if (a.size == 0) {
        out = b;
        out.negative = b_negative;
        return;
    }
    if (a.negative == b_negative) {
        add_magnitudes(a, b, out);
        out.negative = a.negative;
        return;
    }
    const int order = compare_magnitudes(a, b);
    if (order == 0) {
        out.size = 0;
        out.negative = false;
    } else if (order > 0) {
        const bool negative = a.negative;
        subtract_magnitudes(a, b, out);
        out.negative = negative;
    } else {
        subtract_magnitudes(b, a, out);
        out.negative = b_negative;
    }
}

}  // namespace exact_detail

// out = a + b (out may alias a or b).
inline void exact_add(const ExactInteger& a, const ExactInteger& b, ExactInteger& out) {
    exact_detail::add_signed(a, b, b.negative, out);
}

// out = a - b (out may alias a or b).
inline void exact_subtract(const ExactInteger& a, const ExactInteger& b, ExactInteger& out) {
    exact_detail::add_signed(a, b, !b.negative && b.size != 0, out);
}

// out = a * b (out must not alias a or b; a.size + b.size <= kCapacity).
inline void exact_multiply(const ExactInteger& a, const ExactInteger& b, ExactInteger& out) {
    if (a.size == 0 || b.size == 0) {
        out.size = 0;
        out.negative = false;
        return;
    }
    const int n = a.size, m = b.size;
    for (int i = 0; i < n + m; ++i) out.limb[i] = 0;
    for (int i = 0; i < n; ++i) {
        uint64_t carry = 0;
        const uint64_t x = a.limb[i];
        for (int j = 0; j < m; ++j) {
            const uint64_t t = x * b.limb[j] + out.limb[i + j] + carry;
            out.limb[i + j] = uint32_t(t);
            carry = t >> 32;
        }
        out.limb[i + m] = uint32_t(carry);
    }
    out.size = out.limb[n + m - 1] != 0 ? n + m : n + m - 1;
    out.negative = a.negative != b.negative;
}

}  // namespace tetprobe
