// Incremental 64-bit FNV-1a hashing of simulation state, for determinism checks (`state_hash`).
// Only hash values whose bytes are fully defined: integers and floats field by field, never structs
// with padding.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <type_traits>
#include <vector>

namespace core {

class Hasher {
public:
    void bytes(const void* data, std::size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) {
            m_h ^= p[i];
            m_h *= 0x100000001B3ull;
        }
    }
    template <typename T>
    requires std::is_arithmetic_v<T> || std::is_enum_v<T>
    void add(T value) {
        if constexpr (std::is_floating_point_v<T>) {
            if (value == T(0)) value = T(0); // -0 and +0 hash alike
        }
        bytes(&value, sizeof value);
    }
    // An array of floats, as add() would hash them one by one as far as equality goes (-0 as +0; the same
    // arrays give the same value on every machine), but two floats to a 64-bit word in eight independent lanes
    // of xor and multiply, each lane mixed and folded in at the end: about 25 times faster than add() per
    // float, for the hair nodes (stateHashBench). Any one changed float changes the value: each lane step is
    // a bijection of the lane.
    void floats(const float* p, std::size_t n) {
        const auto bits = [](float f) {
            std::uint32_t b;
            std::memcpy(&b, &f, sizeof b);
            return b == 0x80000000u ? 0u : b;
        };
        constexpr std::uint64_t kOdd = 0x9E3779B97F4A7C15ull;
        std::uint64_t lane[8];
        for (std::size_t l = 0; l < 8; ++l) lane[l] = m_h + kOdd * (l + 1);
        std::size_t i = 0;
        for (; i + 16 <= n; i += 16) {
            for (std::size_t l = 0; l < 8; ++l) {
                const std::uint64_t word = bits(p[i + 2 * l]) | (std::uint64_t{bits(p[i + 2 * l + 1])} << 32);
                lane[l] = (lane[l] ^ word) * kOdd;
            }
        }
        for (std::uint64_t l : lane) add(l ^ (l >> 29));
        for (; i < n; ++i) add(bits(p[i]));
        add(static_cast<std::uint64_t>(n));
    }
    void add(std::string_view s) {
        add(static_cast<std::uint64_t>(s.size()));
        bytes(s.data(), s.size());
    }
    std::uint64_t value() const { return m_h; }

private:
    std::uint64_t m_h = 0xCBF29CE484222325ull;
};

// Hashes a field list (physics::visitHairState, game/state_fields.h) value by value: numbers, bools and enums
// as Hasher::add does, vectors and quaternions (anything with a static length() and operator[]) component by
// component, node arrays with Hasher::floats. Names are not hashed: the list's order is the layout.
struct HashFields {
    Hasher& h;
    template <typename T>
    void value(const char* /*name*/, const T& v) {
        if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
            h.add(v);
        } else {
            for (decltype(T::length()) i = 0; i < T::length(); ++i) h.add(v[i]);
        }
    }
    void nodes(const char* /*name*/, const std::vector<float>& a) { h.floats(a.data(), a.size()); }
};

} // namespace core
