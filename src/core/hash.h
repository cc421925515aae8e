// Incremental 64-bit FNV-1a hashing of simulation state, for determinism checks (`state_hash`).
// Only hash values whose bytes are fully defined: integers and floats field by field, never structs
// with padding.
#pragma once
#include <cstdint>
#include <cstring>
#include <string_view>
#include <type_traits>

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
    void add(std::string_view s) {
        add(static_cast<std::uint64_t>(s.size()));
        bytes(s.data(), s.size());
    }
    std::uint64_t value() const { return m_h; }

private:
    std::uint64_t m_h = 0xCBF29CE484222325ull;
};

} // namespace core
