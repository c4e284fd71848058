// Mitsuba's `ply` shape: a Stanford PLY triangle mesh.
//
// Supported: `filename`, `face_normals` (default false), `flip_normals`, `to_world`. Formats ascii,
// binary_little_endian and binary_big_endian; vertex x y z, optional nx ny nz and texture coordinates (u v, s t or
// texture_u texture_v); faces as vertex_indices / vertex_index lists (polygons are fanned into triangles). A mesh
// without normals gets Mitsuba's angle-weighted smooth vertex normals unless face_normals is set. Other element
// properties (vertex colours, ...) are skipped, as in Mitsuba's surface shading. The whole file is parsed from
// memory with every count checked against the bytes that remain, so a hostile header (a list of 4e9 items, an
// element of 1e18 rows, a negative index) is an error naming the file, never an allocation, a hang or an
// undefined cast; values must be finite.
// Differences: none.
#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <utility>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

enum class PlyType { i8, u8, i16, u16, i32, u32, f32, f64 };
enum class PlyFormat { ascii, little_endian, big_endian };

std::size_t type_size(PlyType t) {
    switch (t) {
        case PlyType::i8: case PlyType::u8: return 1;
        case PlyType::i16: case PlyType::u16: return 2;
        case PlyType::i32: case PlyType::u32: case PlyType::f32: return 4;
        case PlyType::f64: return 8;
    }
    return 1;
}

std::pair<double, double> type_range(PlyType t) {
    switch (t) {
        case PlyType::i8: return {-128.0, 127.0};
        case PlyType::u8: return {0.0, 255.0};
        case PlyType::i16: return {-32768.0, 32767.0};
        case PlyType::u16: return {0.0, 65535.0};
        case PlyType::i32: return {-2147483648.0, 2147483647.0};
        case PlyType::u32: return {0.0, 4294967295.0};
        case PlyType::f32: return {-double(std::numeric_limits<float>::max()), double(std::numeric_limits<float>::max())};
        case PlyType::f64: break;
    }
    return {-std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
}

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::f32;
    bool is_list = false;
    PlyType count_type = PlyType::u8;
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

class PlyReader {
public:
    PlyReader(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

    TriangleMesh read() {
        read_header();
        TriangleMesh mesh;
        for (const PlyElement& e : elements_) read_element(e, mesh);
        if (format_ == PlyFormat::ascii) skip_space();
        if (pos_ != bytes_.size())
            error("{} bytes after the last element (the header's counts do not match the data)", bytes_.size() - pos_);
        if (mesh.triangles.empty()) error("no faces");
        for (const auto& t : mesh.triangles)
            for (std::uint32_t index : t)
                if (index >= mesh.positions.size())
                    error("face vertex index {} out of range ({} vertices)", index, mesh.positions.size());
        if (mesh.normals.size() != mesh.positions.size()) mesh.normals.clear();
        if (mesh.uvs.size() != mesh.positions.size()) mesh.uvs.clear();
        return mesh;
    }

private:
    template <typename... Args>
    [[noreturn]] void error(fmt::format_string<Args...> format, Args&&... args) const {
        throw Error(fmt::format("{}: ", name_) + fmt::format(format, std::forward<Args>(args)...));
    }
    template <typename... Args>
    [[noreturn]] void header_error(int line, fmt::format_string<Args...> format, Args&&... args) const {
        throw Error(fmt::format("{}:{}: ", name_, line) + fmt::format(format, std::forward<Args>(args)...));
    }

    PlyType parse_type(const std::string& word, int line) const {
        if (word == "char" || word == "int8") return PlyType::i8;
        if (word == "uchar" || word == "uint8") return PlyType::u8;
        if (word == "short" || word == "int16") return PlyType::i16;
        if (word == "ushort" || word == "uint16") return PlyType::u16;
        if (word == "int" || word == "int32") return PlyType::i32;
        if (word == "uint" || word == "uint32") return PlyType::u32;
        if (word == "float" || word == "float32") return PlyType::f32;
        if (word == "double" || word == "float64") return PlyType::f64;
        header_error(line, "unknown PLY property type '{}'", printable(word));
    }

    void read_header() {
        int line_number = 0;
        bool have_format = false;
        while (true) {
            if (pos_ >= bytes_.size()) error("the header has no 'end_header' line");
            const std::size_t end = std::min(bytes_.find('\n', pos_), bytes_.size());
            std::string_view line = bytes_.substr(pos_, end - pos_);
            pos_ = std::min(end + 1, bytes_.size());
            ++line_number;
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
            std::vector<std::string> words;
            for (std::size_t i = 0; i < line.size();) {
                while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
                std::size_t j = i;
                while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
                if (j > i) words.emplace_back(line.substr(i, j - i));
                i = j;
            }
            if (line_number == 1) {
                if (words.size() != 1 || words[0] != "ply") error("not a PLY file (the first line is not 'ply')");
                continue;
            }
            if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
            const std::string& tag = words[0];
            if (tag == "end_header") break;
            if (tag == "format") {
                if (words.size() != 3 || words[2] != "1.0") header_error(line_number, "expected 'format <type> 1.0'");
                if (words[1] == "ascii") format_ = PlyFormat::ascii;
                else if (words[1] == "binary_little_endian") format_ = PlyFormat::little_endian;
                else if (words[1] == "binary_big_endian") format_ = PlyFormat::big_endian;
                else header_error(line_number, "unknown PLY format '{}'", printable(words[1]));
                have_format = true;
            } else if (tag == "element") {
                if (words.size() != 3) header_error(line_number, "expected 'element <name> <count>'");
                PlyElement e;
                e.name = words[1];
                char* end_ptr = nullptr;
                errno = 0;
                const unsigned long long count = std::strtoull(words[2].c_str(), &end_ptr, 10);
                if (words[2][0] == '-' || end_ptr != words[2].c_str() + words[2].size() || errno == ERANGE)
                    header_error(line_number, "element count '{}' is not a non-negative integer", printable(words[2]));
                e.count = count;
                if (std::any_of(elements_.begin(), elements_.end(), [&](const PlyElement& d) { return d.name == e.name; }))
                    header_error(line_number, "element '{}' is declared twice", printable(e.name));
                elements_.push_back(std::move(e));
            } else if (tag == "property") {
                if (elements_.empty()) header_error(line_number, "property before any element");
                PlyProperty p;
                if (words.size() == 5 && words[1] == "list") {
                    p.is_list = true;
                    p.count_type = parse_type(words[2], line_number);
                    if (p.count_type == PlyType::f32 || p.count_type == PlyType::f64)
                        header_error(line_number, "a list count must have an integer type, got '{}'", words[2]);
                    p.type = parse_type(words[3], line_number);
                    p.name = words[4];
                } else if (words.size() == 3 && words[1] != "list") {
                    p.type = parse_type(words[1], line_number);
                    p.name = words[2];
                } else {
                    header_error(line_number, "expected 'property <type> <name>' or 'property list <count type> "
                                              "<item type> <name>'");
                }
                elements_.back().properties.push_back(std::move(p));
            } else {
                header_error(line_number, "unknown PLY header line '{}'", printable(tag));
            }
        }
        if (!have_format) error("the header has no 'format' line");
        for (const PlyElement& e : elements_)
            if (e.count > 0 && e.properties.empty()) error("element '{}' has {} rows but no properties", printable(e.name), e.count);
    }

    // ---- values

    void skip_space() {
        while (pos_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
    }

    double ascii_value(PlyType type, const char* what) {
        skip_space();
        std::size_t end = pos_;
        while (end < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[end]))) ++end;
        if (end == pos_) error("the data end early while reading {}", what);
        const std::string token(bytes_.substr(pos_, end - pos_));
        pos_ = end;
        char* end_ptr = nullptr;
        errno = 0;
        const double v = std::strtod(token.c_str(), &end_ptr);
        if (end_ptr != token.c_str() + token.size() || !std::isfinite(v) || (errno == ERANGE && std::abs(v) > 1.0))
            error("'{}' in {} is not a finite number", printable(token), what);
        if (type != PlyType::f32 && type != PlyType::f64 && v != std::floor(v))
            error("'{}' in {} is not an integer", printable(token), what);
        // A value must fit its declared type, as it would in a binary file (a uchar list count of 1e28 does not).
        const auto [lo, hi] = type_range(type);
        if (v < lo || v > hi) error("{} in {} does not fit its type (range {:g} to {:g})", printable(token), what, lo, hi);
        return v;
    }

    template <typename T>
    T binary(const char* what) {
        if (bytes_.size() - pos_ < sizeof(T)) error("the data end early while reading {}", what);
        std::array<char, sizeof(T)> raw;
        std::memcpy(raw.data(), bytes_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        if ((format_ == PlyFormat::big_endian) == (std::endian::native == std::endian::little))
            std::reverse(raw.begin(), raw.end());
        return std::bit_cast<T>(raw);
    }

    double value(PlyType type, const char* what) {
        if (format_ == PlyFormat::ascii) return ascii_value(type, what);
        double v = 0;
        switch (type) {
            case PlyType::i8: v = binary<std::int8_t>(what); break;
            case PlyType::u8: v = binary<std::uint8_t>(what); break;
            case PlyType::i16: v = binary<std::int16_t>(what); break;
            case PlyType::u16: v = binary<std::uint16_t>(what); break;
            case PlyType::i32: v = binary<std::int32_t>(what); break;
            case PlyType::u32: v = binary<std::uint32_t>(what); break;
            case PlyType::f32: v = binary<float>(what); break;
            case PlyType::f64: v = binary<double>(what); break;
        }
        if (!std::isfinite(v)) error("{} is {} (values must be finite)", what, v);
        return v;
    }

    // The fewest bytes `count` more items of `size` bytes each can take: an upper bound on counts read from the
    // file, so that no count can make the reader allocate or loop beyond what the file holds.
    void require_room(std::uint64_t count, std::size_t size, const char* what) const {
        if (count == 0) return;  // an empty element may have no properties (size 0)
        const std::uint64_t per_item = format_ == PlyFormat::ascii ? 1 : size;  // ascii: at least one digit each
        if (count > (bytes_.size() - pos_) / per_item)
            error("{} claims {} items, more than the {} bytes left in the file hold", what, count, bytes_.size() - pos_);
    }

    // ---- elements

    void read_element(const PlyElement& e, TriangleMesh& mesh) {
        const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
        std::size_t row_bytes = 0;
        for (const PlyProperty& p : e.properties) row_bytes += p.is_list ? type_size(p.count_type) : type_size(p.type);
        require_room(e.count, row_bytes, ("element '" + e.name + "'").c_str());
        const auto has = [&](const char* n) {
            return std::any_of(e.properties.begin(), e.properties.end(), [&](const PlyProperty& p) { return p.name == n && !p.is_list; });
        };
        if (is_vertex && (!has("x") || !has("y") || !has("z"))) error("the vertex element has no x, y and z");
        const bool normals = is_vertex && has("nx") && has("ny") && has("nz");
        const bool uvs = is_vertex && ((has("u") && has("v")) || (has("s") && has("t")) ||
                                        (has("texture_u") && has("texture_v")));
        std::vector<double> indices;
        for (std::uint64_t row = 0; row < e.count; ++row) {
            Vec3 p, n;
            Vec2 uv;
            for (const PlyProperty& prop : e.properties) {
                if (prop.is_list) {
                    const double count = value(prop.count_type, "a list count");
                    if (count < 0) error("{} row {}: list '{}' has a negative count {}", e.name, row, prop.name, count);
                    const auto items = static_cast<std::uint64_t>(count);
                    require_room(items, type_size(prop.type), "a list");
                    const bool face_list = is_face && (prop.name == "vertex_indices" || prop.name == "vertex_index");
                    indices.clear();
                    for (std::uint64_t k = 0; k < items; ++k) {
                        const double x = value(prop.type, "a list item");
                        if (face_list) indices.push_back(x);
                    }
                    if (face_list) add_face(indices, row, mesh);
                    continue;
                }
                const double v = value(prop.type, "a property");
                if (!is_vertex) continue;
                const std::string& name = prop.name;
                if (name == "x") p.x = v;
                else if (name == "y") p.y = v;
                else if (name == "z") p.z = v;
                else if (name == "nx") n.x = v;
                else if (name == "ny") n.y = v;
                else if (name == "nz") n.z = v;
                else if (name == "u" || name == "s" || name == "texture_u") uv.x = v;
                else if (name == "v" || name == "t" || name == "texture_v") uv.y = v;
            }
            if (!is_vertex) continue;
            mesh.positions.push_back(p);
            if (normals) {
                if (!(n.length() > 0)) error("vertex {} has the zero normal", row);
                mesh.normals.push_back(normalize(n));
            }
            if (uvs) mesh.uvs.push_back(uv);
        }
    }

    void add_face(const std::vector<double>& indices, std::uint64_t row, TriangleMesh& mesh) {
        if (indices.size() < 3) error("face {} has {} vertices (at least 3 are needed)", row, indices.size());
        std::vector<std::uint32_t> idx;
        for (double x : indices) {
            if (!(x >= 0 && x < 4294967295.0)) error("face {} has the vertex index {}", row, x);
            idx.push_back(static_cast<std::uint32_t>(x));
        }
        for (std::size_t k = 1; k + 1 < idx.size(); ++k) mesh.triangles.push_back({idx[0], idx[k], idx[k + 1]});
    }

    std::string_view bytes_;
    const std::string& name_;
    std::size_t pos_ = 0;
    PlyFormat format_ = PlyFormat::ascii;
    std::vector<PlyElement> elements_;
};

}  // namespace

TriangleMesh parse_ply(std::string_view bytes, const std::string& name) { return PlyReader(bytes, name).read(); }

TriangleMesh load_ply(const std::filesystem::path& path) {
    return parse_ply(read_input_file(path, "PLY file", kMaxMeshFileBytes), path.string());
}

ShapeGeometry plugins::ply(Properties& props) {
    TriangleMesh mesh = load_ply(props.get_file("filename"));
    finish_mesh(mesh, props.get_bool("face_normals", false), props.get_transform("to_world"),
                props.get_bool("flip_normals", false));
    return mesh;
}

}  // namespace surfscatter::render
