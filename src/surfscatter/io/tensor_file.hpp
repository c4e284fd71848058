#pragma once
// Mitsuba's `tensor_file` container, the file format of the RGL measured BSDFs (Dupuy & Jakob 2018; read by Mitsuba 3's
// and pbrt-v4's `measured`): the 12-byte magic "tensor_file\0", a version (two bytes, 1.0), a little-endian u32 field
// count, then per field its name (u16 length + bytes), rank (u16), dtype (u8, Mitsuba's Struct::Type numbering),
// data offset (u64) and shape (rank x u64); each field's data is contiguous, row-major (last index fastest),
// little-endian, at its offset (8-byte aligned when written here).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace surfscatter::io {

// Mitsuba's Struct::Type codes.
enum class TensorDtype : std::uint8_t {
    UInt8 = 1, Int8 = 2, UInt16 = 3, Int16 = 4, UInt32 = 5, Int32 = 6, UInt64 = 7, Int64 = 8, Float16 = 9,
    Float32 = 10, Float64 = 11
};
std::size_t dtype_size(TensorDtype dtype);
const char* dtype_name(TensorDtype dtype);

struct TensorField {
    std::string name;
    TensorDtype dtype = TensorDtype::Float32;
    std::vector<std::uint64_t> shape;
    std::string bytes;  // the raw little-endian data, element_count() * dtype_size(dtype) bytes

    std::uint64_t element_count() const;
    // The data converted to double (integer and float dtypes; Float16 is refused as no RGL file uses it).
    std::vector<double> values() const;
    std::vector<float> floats() const;  // Float32 fields only, else an Error naming the field

    static TensorField of_floats(std::string name, std::vector<std::uint64_t> shape, const std::vector<float>& data);
    static TensorField of_bytes(std::string name, TensorDtype dtype, std::vector<std::uint64_t> shape,
                                std::string bytes);
};

struct TensorFile {
    std::vector<TensorField> fields;
    // The field of that name, or nullptr.
    const TensorField* find(const std::string& name) const;
    // The field of that name; an Error naming `origin` (the file) and the field if it is missing.
    const TensorField& at(const std::string& name, const std::string& origin) const;
};

// Parses a container from memory; `origin` names it in messages. Every count, offset and shape is checked against
// the size of the data (a truncated or hostile file is an Error, never a read outside the buffer).
TensorFile parse_tensor_file(const std::string& bytes, const std::string& origin);
TensorFile read_tensor_file(const std::filesystem::path& path);
std::string serialize_tensor_file(const TensorFile& file);
// Written atomically (core/paths.hpp).
void write_tensor_file(const std::filesystem::path& path, const TensorFile& file);

}  // namespace surfscatter::io
