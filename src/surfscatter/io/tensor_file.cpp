#include "surfscatter/io/tensor_file.hpp"

#include <bit>
#include <cstring>
#include <limits>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/core/output_files.hpp"

namespace surfscatter::io {

static_assert(std::endian::native == std::endian::little, "tensor files are little-endian");

namespace {

constexpr char kMagic[12] = {'t', 'e', 'n', 's', 'o', 'r', '_', 'f', 'i', 'l', 'e', '\0'};
// The largest RGL files are tens of MB (spectral, anisotropic); far beyond, small enough to fail fast.
constexpr std::uint64_t kMaxTensorFileBytes = std::uint64_t{2} << 30;

class Reader {
public:
    Reader(const std::string& bytes, const std::string& origin) : bytes_(bytes), origin_(origin) {}
    template <typename T>
    T get(const char* what) {
        if (bytes_.size() - pos_ < sizeof(T))
            fail("tensor file {}: truncated header (reading {} at byte {})", printable(origin_, kShownPathChars), what,
                 pos_);
        T value;
        std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return value;
    }
    std::string get_string(std::size_t length, const char* what) {
        if (bytes_.size() - pos_ < length)
            fail("tensor file {}: truncated header (reading {} at byte {})", printable(origin_, kShownPathChars), what,
                 pos_);
        std::string s = bytes_.substr(pos_, length);
        pos_ += length;
        return s;
    }

private:
    const std::string& bytes_;
    const std::string& origin_;
    std::size_t pos_ = 0;
};

bool known_dtype(std::uint8_t code) { return code >= 1 && code <= 11; }

template <typename T>
void append(std::string& out, T value) {
    char buffer[sizeof(T)];
    std::memcpy(buffer, &value, sizeof(T));
    out.append(buffer, sizeof(T));
}

}  // namespace

std::size_t dtype_size(TensorDtype dtype) {
    switch (dtype) {
        case TensorDtype::UInt8: case TensorDtype::Int8: return 1;
        case TensorDtype::UInt16: case TensorDtype::Int16: case TensorDtype::Float16: return 2;
        case TensorDtype::UInt32: case TensorDtype::Int32: case TensorDtype::Float32: return 4;
        case TensorDtype::UInt64: case TensorDtype::Int64: case TensorDtype::Float64: return 8;
    }
    fail("tensor file: unknown dtype code {}", static_cast<int>(dtype));
}

const char* dtype_name(TensorDtype dtype) {
    static const char* const names[] = {"uint8", "int8", "uint16", "int16", "uint32", "int32", "uint64", "int64",
                                        "float16", "float32", "float64"};
    const auto code = static_cast<int>(dtype);
    return code >= 1 && code <= 11 ? names[code - 1] : "unknown";
}

std::uint64_t TensorField::element_count() const {
    std::uint64_t n = 1;
    for (std::uint64_t s : shape) n *= s;  // shapes are checked against the file size when read
    return n;
}

std::vector<double> TensorField::values() const {
    const std::uint64_t n = element_count();
    std::vector<double> out(n);
    const char* p = bytes.data();
    auto load = [&]<typename T>(T) {
        for (std::uint64_t i = 0; i < n; ++i) {
            T v;
            std::memcpy(&v, p + i * sizeof(T), sizeof(T));
            out[i] = static_cast<double>(v);
        }
    };
    switch (dtype) {
        case TensorDtype::UInt8: load(std::uint8_t{}); break;
        case TensorDtype::Int8: load(std::int8_t{}); break;
        case TensorDtype::UInt16: load(std::uint16_t{}); break;
        case TensorDtype::Int16: load(std::int16_t{}); break;
        case TensorDtype::UInt32: load(std::uint32_t{}); break;
        case TensorDtype::Int32: load(std::int32_t{}); break;
        case TensorDtype::UInt64: load(std::uint64_t{}); break;
        case TensorDtype::Int64: load(std::int64_t{}); break;
        case TensorDtype::Float32: load(float{}); break;
        case TensorDtype::Float64: load(double{}); break;
        case TensorDtype::Float16: fail("tensor field '{}': float16 data are not supported", printable(name));
    }
    return out;
}

std::vector<float> TensorField::floats() const {
    if (dtype != TensorDtype::Float32)
        fail("tensor field '{}' is {}, expected float32", printable(name), dtype_name(dtype));
    std::vector<float> out(element_count());
    std::memcpy(out.data(), bytes.data(), out.size() * sizeof(float));
    return out;
}

TensorField TensorField::of_floats(std::string name, std::vector<std::uint64_t> shape, const std::vector<float>& data) {
    std::string bytes(data.size() * sizeof(float), '\0');
    std::memcpy(bytes.data(), data.data(), bytes.size());
    return of_bytes(std::move(name), TensorDtype::Float32, std::move(shape), std::move(bytes));
}

TensorField TensorField::of_bytes(std::string name, TensorDtype dtype, std::vector<std::uint64_t> shape,
                                  std::string bytes) {
    TensorField f{std::move(name), dtype, std::move(shape), std::move(bytes)};
    if (f.bytes.size() != f.element_count() * dtype_size(dtype))
        fail("tensor field '{}': {} bytes for {} elements of {}", printable(f.name), f.bytes.size(), f.element_count(),
             dtype_name(dtype));
    return f;
}

const TensorField* TensorFile::find(const std::string& name) const {
    for (const auto& f : fields)
        if (f.name == name) return &f;
    return nullptr;
}

const TensorField& TensorFile::at(const std::string& name, const std::string& origin) const {
    if (const TensorField* f = find(name)) return *f;
    fail("tensor file {}: no field '{}'", printable(origin, kShownPathChars), name);
}

TensorFile parse_tensor_file(const std::string& bytes, const std::string& origin) {
    const std::string shown = printable(origin, kShownPathChars);
    if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
        fail("tensor file {}: not a tensor file (no 'tensor_file' magic)", shown);
    Reader in(bytes, origin);
    in.get_string(sizeof(kMagic), "magic");
    const auto major = in.get<std::uint8_t>("version"), minor = in.get<std::uint8_t>("version");
    if (major != 1 || minor != 0) fail("tensor file {}: version {}.{}, expected 1.0", shown, major, minor);
    const auto count = in.get<std::uint32_t>("field count");
    if (count > 4096) fail("tensor file {}: {} fields (at most 4096)", shown, count);
    TensorFile file;
    for (std::uint32_t i = 0; i < count; ++i) {
        TensorField f;
        f.name = in.get_string(in.get<std::uint16_t>("name length"), "field name");
        const auto rank = in.get<std::uint16_t>("rank");
        const auto code = in.get<std::uint8_t>("dtype");
        const auto offset = in.get<std::uint64_t>("offset");
        if (!known_dtype(code)) fail("tensor file {}: field '{}' has unknown dtype code {}", shown, printable(f.name), code);
        f.dtype = static_cast<TensorDtype>(code);
        std::uint64_t elements = 1;
        for (std::uint16_t k = 0; k < rank; ++k) {
            const auto extent = in.get<std::uint64_t>("shape");
            f.shape.push_back(extent);
            if (extent != 0 && elements > bytes.size() / extent)
                fail("tensor file {}: field '{}' is larger than the file", shown, printable(f.name));
            elements *= extent;
        }
        const std::uint64_t size = elements * dtype_size(f.dtype);
        if (size > bytes.size() || offset > bytes.size() - size)
            fail("tensor file {}: field '{}' ({} bytes at offset {}) lies outside the file ({} bytes)", shown,
                 printable(f.name), size, offset, bytes.size());
        if (file.find(f.name)) fail("tensor file {}: field '{}' appears twice", shown, printable(f.name));
        f.bytes = bytes.substr(offset, size);
        file.fields.push_back(std::move(f));
    }
    return file;
}

TensorFile read_tensor_file(const std::filesystem::path& path) {
    return parse_tensor_file(read_input_file(path, "tensor file", kMaxTensorFileBytes), path.string());
}

std::string serialize_tensor_file(const TensorFile& file) {
    std::string header(kMagic, sizeof(kMagic));
    append<std::uint8_t>(header, 1);
    append<std::uint8_t>(header, 0);
    append<std::uint32_t>(header, static_cast<std::uint32_t>(file.fields.size()));
    std::size_t header_size = header.size();
    for (const auto& f : file.fields) header_size += 2 + f.name.size() + 2 + 1 + 8 + 8 * f.shape.size();
    auto align = [](std::uint64_t x) { return (x + 7) / 8 * 8; };
    std::uint64_t offset = align(header_size);
    std::string data;
    for (const auto& f : file.fields) {
        if (f.name.size() > std::numeric_limits<std::uint16_t>::max() || f.shape.size() > 0xffff)
            fail("tensor field '{}': name or rank too long to write", printable(f.name));
        append<std::uint16_t>(header, static_cast<std::uint16_t>(f.name.size()));
        header += f.name;
        append<std::uint16_t>(header, static_cast<std::uint16_t>(f.shape.size()));
        append<std::uint8_t>(header, static_cast<std::uint8_t>(f.dtype));
        append<std::uint64_t>(header, offset);
        for (auto s : f.shape) append<std::uint64_t>(header, s);
        const std::uint64_t padded = align(f.bytes.size());
        data += f.bytes;
        data.append(padded - f.bytes.size(), '\0');
        offset += padded;
    }
    header.append(align(header.size()) - header.size(), '\0');
    return header + data;
}

void write_tensor_file(const std::filesystem::path& path, const TensorFile& file) {
    write_file_atomically(path, serialize_tensor_file(file));
}

}  // namespace surfscatter::io
