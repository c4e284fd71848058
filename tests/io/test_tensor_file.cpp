// The tensor_file container (io/tensor_file.hpp): a written file reads back field by field; every truncation of a
// valid file is an Error, never a read outside the buffer.
#include <gtest/gtest.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/io/tensor_file.hpp"

using namespace surfscatter;
using namespace surfscatter::io;

TEST(TensorFile, RoundTrip) {
    TensorFile f;
    f.fields.push_back(TensorField::of_floats("a", {2, 3}, {1, 2, 3, 4, 5, 6.5f}));
    f.fields.push_back(TensorField::of_bytes("text", TensorDtype::UInt8, {5}, "hello"));
    std::string u32(8, '\0');
    u32[0] = 1;
    f.fields.push_back(TensorField::of_bytes("version", TensorDtype::UInt32, {2}, u32));
    const std::string bytes = serialize_tensor_file(f);
    EXPECT_EQ(bytes.substr(0, 12), std::string("tensor_file\0", 12));
    const TensorFile g = parse_tensor_file(bytes, "memory");
    ASSERT_EQ(g.fields.size(), 3u);
    EXPECT_EQ(g.at("a", "memory").shape, (std::vector<std::uint64_t>{2, 3}));
    EXPECT_EQ(g.at("a", "memory").floats(), (std::vector<float>{1, 2, 3, 4, 5, 6.5f}));
    EXPECT_EQ(g.at("text", "memory").bytes, "hello");
    EXPECT_EQ(g.at("version", "memory").values(), (std::vector<double>{1, 0}));
    EXPECT_THROW(g.at("missing", "memory"), Error);
    EXPECT_THROW(g.at("text", "memory").floats(), Error);
}

TEST(TensorFile, TruncationsAndBadFieldsAreErrors) {
    TensorFile f;
    f.fields.push_back(TensorField::of_floats("a", {4}, {1, 2, 3, 4}));
    const std::string bytes = serialize_tensor_file(f);
    for (std::size_t n = 0; n < bytes.size(); ++n) EXPECT_THROW(parse_tensor_file(bytes.substr(0, n), "cut"), Error) << n;
    std::string huge = bytes;
    huge[18 + 2 + 1 + 2 + 1 + 8] = '\x7f';  // the shape's first byte: 127 elements, beyond the file
    EXPECT_THROW(parse_tensor_file(huge, "huge"), Error);
    std::string dtype = bytes;
    dtype[18 + 2 + 1 + 2] = 42;
    EXPECT_THROW(parse_tensor_file(dtype, "dtype"), Error);
}
