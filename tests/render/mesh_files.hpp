#pragma once
// Mitsuba's .serialized mesh format written by the tests (the layout Mitsuba 3 documents for the plugin), for the
// reader in shapes/serialized.cpp.
#include <array>
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <zlib.h>

#include "surfscatter/math/vec.hpp"

namespace surfscatter::render::test {

template <typename T>
inline void put(std::vector<std::uint8_t>& out, T value) {
    static_assert(std::endian::native == std::endian::little);
    const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
    out.insert(out.end(), p, p + sizeof value);
}

// One mesh of a .serialized file (Mitsuba's documented layout), compressed with zlib.
inline std::vector<std::uint8_t> serialized_mesh(int version, const std::vector<Vec3>& positions, const std::vector<Vec3>& normals,
                                          const std::vector<Vec2>& uvs, const std::vector<std::array<std::uint32_t, 3>>& triangles,
                                          bool double_precision) {
    std::vector<std::uint8_t> raw;
    std::uint32_t flags = double_precision ? 0x2000 : 0x1000;
    if (!normals.empty()) flags |= 0x0001;
    if (!uvs.empty()) flags |= 0x0002;
    put(raw, flags);
    if (version == 4)
        for (char c : std::string("mesh")) raw.push_back(static_cast<std::uint8_t>(c));
    if (version == 4) raw.push_back(0);
    put(raw, static_cast<std::uint64_t>(positions.size()));
    put(raw, static_cast<std::uint64_t>(triangles.size()));
    const auto real = [&](double v) { double_precision ? put(raw, v) : put(raw, static_cast<float>(v)); };
    for (const Vec3& p : positions) real(p.x), real(p.y), real(p.z);
    for (const Vec3& n : normals) real(n.x), real(n.y), real(n.z);
    for (const Vec2& t : uvs) real(t.x), real(t.y);
    for (const auto& t : triangles) put(raw, t[0]), put(raw, t[1]), put(raw, t[2]);
    uLongf size = compressBound(static_cast<uLong>(raw.size()));
    std::vector<std::uint8_t> out;
    put(out, static_cast<std::uint16_t>(0x041C));
    put(out, static_cast<std::uint16_t>(version));
    std::vector<std::uint8_t> compressed(size);
    EXPECT_EQ(compress(compressed.data(), &size, raw.data(), static_cast<uLong>(raw.size())), Z_OK);
    out.insert(out.end(), compressed.begin(), compressed.begin() + static_cast<long>(size));
    return out;
}


}  // namespace surfscatter::render::test
