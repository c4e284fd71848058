#include "surfscatter/heightmap/opdx.hpp"

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/binary.hpp"
#include "surfscatter/heightmap/parse.hpp"

namespace surfscatter::heightmap {

namespace {

constexpr std::string_view kOpdxMagic("VCA DATA\x01\x00\x00\x55", 12);
constexpr int kMaxDepth = 32;  // containers nest a few levels; a hostile file cannot exhaust the stack

enum Type : std::uint8_t {
    kMatrix = 0x00, kBoolean = 0x01, kInt16 = 0x04, kUInt16 = 0x05, kInt32 = 0x06, kUInt32 = 0x07, kInt64 = 0x0a,
    kUInt64 = 0x0b, kFloat = 0x0c, kDouble = 0x0d, kTypeId = 0x0e, kString = 0x12, kQuantity = 0x13,
    kTimeStamp = 0x15, kUnits = 0x18, kDoubleArray = 0x40, kStringList = 0x42, kRawData = 0x46, kRawData2d = 0x47,
    kPositionRawData = 0x7c, kContainer = 0x7d, kTerminator = 0x7f,
};

// What an item holds, as far as the reader needs it.
struct Item {
    double number = 0.0;               // integers, floats, a quantity's or unit's value
    std::string text;                  // strings; a quantity's or unit's symbol
    std::vector<std::string> list;     // string lists
    std::size_t data_at = 0, data_bytes = 0;  // arrays and matrices: where their data lie
    std::uint64_t rows = 0, columns = 0;      // matrices
};

class Parser {
public:
    Parser(std::string_view bytes, const std::string& path) : in_(bytes, path, kOpdxMagic.size()) {}

    std::map<std::string, Item> parse() {
        while (!in_.at_end())
            if (!read_item("", 0)) break;
        return std::move(items_);
    }

private:
    std::string name(const char* what) {
        const std::uint32_t length = in_.u32(what);
        return std::string(in_.bytes(length, what));
    }
    std::size_t varlen(const std::string& at) {
        const std::uint8_t size = in_.u8("a length's size");
        switch (size) {
            case 1: return in_.u8("a length");
            case 2: return in_.u16("a length");
            case 4: return in_.u32("a length");
            default: fail("{}: OPDx item '{}': a length of {} bytes (1, 2 or 4 expected)", in_.path(), printable(at), size);
        }
    }
    // The end of a block of `length` bytes starting here, checked against the file.
    std::size_t block_end(std::size_t length, const std::string& at) {
        if (length > in_.remaining())
            fail("{}: OPDx item '{}' of {} bytes at byte {} runs past the end of the file", in_.path(), printable(at),
                 length, in_.position());
        return in_.position() + length;
    }
    void expect_end(std::size_t end, const std::string& at) {
        if (in_.position() != end)
            fail("{}: OPDx item '{}' ends at byte {}, its length says {}", in_.path(), printable(at), in_.position(), end);
    }
    void unit_body(Item& item) {  // name, symbol, value, 12 bytes
        name("a unit name");
        item.text = name("a unit symbol");
        item.number = in_.f64("a unit value");
        in_.skip(12, "a unit's tail");
    }

    // Reads one item below `prefix`; false at a terminator.
    bool read_item(const std::string& prefix, int depth) {
        const std::string path = prefix + "/" + name("an item name");
        const std::uint8_t type = in_.u8("an item type");
        Item item;
        switch (type) {
            case kTerminator: return false;
            case kContainer: case kRawData: case kRawData2d: {
                if (depth >= kMaxDepth) fail("{}: OPDx containers nested deeper than {} at '{}'", in_.path(), kMaxDepth, printable(path));
                const std::size_t end = block_end(varlen(path), path);
                while (in_.position() < end && read_item(path, depth + 1)) {}
                in_.skip(2, "a container's tail");
                expect_end(end, path);
                return true;
            }
            case kBoolean: item.number = in_.u8(path.c_str()); break;
            case kInt16: item.number = static_cast<std::int16_t>(in_.u16("an int16")); break;
            case kUInt16: item.number = in_.u16("a uint16"); break;
            case kInt32: item.number = static_cast<std::int32_t>(in_.u32("an int32")); break;
            case kUInt32: item.number = in_.u32("a uint32"); break;
            case kInt64: item.number = static_cast<double>(static_cast<std::int64_t>(in_.u64("an int64"))); break;
            case kUInt64: item.number = static_cast<double>(in_.u64("a uint64")); break;
            case kFloat: item.number = in_.f32("a float"); break;
            case kDouble: item.number = in_.f64("a double"); break;
            case kTimeStamp: in_.skip(9, "a time stamp"); break;
            case kString: item.text = std::string(in_.bytes(varlen(path), "a string")); break;
            case kTypeId: name("a type name"); in_.skip(varlen(path), "a type id"); break;
            case kQuantity: {
                const std::size_t end = block_end(varlen(path), path);
                item.number = in_.f64("a quantity's value");
                name("a quantity's name");
                item.text = name("a quantity's symbol");
                if (in_.position() > end) expect_end(end, path);
                in_.seek(end, "a quantity's end");
                break;
            }
            case kUnits: {
                const std::size_t end = block_end(varlen(path), path);
                unit_body(item);
                expect_end(end, path);
                break;
            }
            case kDoubleArray: {
                name("an array's type name");
                item.data_bytes = varlen(path);
                item.data_at = in_.position();
                in_.skip(item.data_bytes, "an array");
                break;
            }
            case kStringList: {
                name("a list's type name");
                const std::size_t end = block_end(varlen(path), path);
                while (in_.position() < end) item.list.push_back(name("a list entry"));
                expect_end(end, path);
                break;
            }
            case kMatrix: {
                name("a matrix's type name");
                in_.u32("a matrix's tag");
                name("a matrix's name");
                const std::size_t length = varlen(path);
                if (length < 8) fail("{}: OPDx matrix '{}' of {} bytes cannot hold its size", in_.path(), printable(path), length);
                const std::size_t end = block_end(length, path);
                item.rows = in_.u32("a matrix's rows");
                item.columns = in_.u32("a matrix's columns");
                item.data_at = in_.position();
                item.data_bytes = end - in_.position();
                in_.seek(end, "a matrix's end");
                break;
            }
            case kPositionRawData: {
                name("a type name");
                const std::size_t end = block_end(varlen(path), path);
                in_.seek(end, "position data");  // the lateral calibration; Extent and Points state the grid
                break;
            }
            default:
                fail("{}: OPDx item '{}' at byte {} has unknown type 0x{:02x}", in_.path(), printable(path),
                     in_.position() - 1, type);
        }
        items_[path] = std::move(item);
        return true;
    }

    binary::Cursor in_;
    std::map<std::string, Item> items_;
};

const Item& find(const std::map<std::string, Item>& items, const std::string& path, const std::string& key) {
    const auto it = items.find(key);
    if (it == items.end()) fail("{}: OPDx item '{}' is missing", path, printable(key));
    return it->second;
}

// A length unit's micrometres, or an Error naming the item.
double unit_um(const std::string& path, const std::string& key, const Item& item) {
    const auto um = parse::length_unit_in_um(item.text);
    if (!um) fail("{}: OPDx item '{}' is in '{}', not a length unit (m, mm, um, nm or pm)", path, printable(key), printable(item.text));
    return *um;
}

double positive_length_um(const std::string& path, const std::map<std::string, Item>& items, const std::string& key) {
    const Item& item = find(items, path, key);
    const double um = item.number * unit_um(path, key, item);
    if (!(std::isfinite(um) && um > 0.0)) fail("{}: OPDx {} = {} {} must be positive", path, printable(key), item.number, printable(item.text));
    return um;
}

std::uint64_t count(const std::string& path, const std::map<std::string, Item>& items, const std::string& key) {
    const double n = find(items, path, key).number;
    if (!(n >= 1.0 && n <= 4294967296.0 && n == std::floor(n))) fail("{}: OPDx {} = {} is not a point count", path, printable(key), n);
    return static_cast<std::uint64_t>(n);
}

// Heights times the channel's DataScale (in um); NaN marks an invalid point.
void scale_heights(const std::string& path, const std::map<std::string, Item>& items, const std::string& prefix,
                   std::vector<double>& heights, std::vector<std::uint8_t>& valid, double& unit) {
    const std::string key = prefix + "/DataScale";
    const Item& scale = find(items, path, key);
    unit = scale.number * unit_um(path, key, scale);
    if (!(std::isfinite(unit) && unit > 0.0)) fail("{}: OPDx {} = {} must be positive", path, printable(key), scale.number);
    for (std::size_t i = 0; i < heights.size(); ++i) {
        if (std::isinf(heights[i])) fail("{}: OPDx height {} is infinite", path, i);
        if (std::isnan(heights[i])) { valid[i] = 0; heights[i] = 0.0; }
        else heights[i] *= unit;
    }
}

}  // namespace

bool is_opdx(std::string_view head) { return head.substr(0, kOpdxMagic.size()) == kOpdxMagic; }

std::variant<HeightMap, LineScan> read_opdx(const std::filesystem::path& file) {
    const std::string path = file.string();
    const std::string bytes = parse::file_bytes(path);
    if (!is_opdx(bytes)) fail("{}: not an OPDx file (no 'VCA DATA' magic)", path);
    const std::map<std::string, Item> items = Parser(bytes, path).parse();
    const std::string& kind = find(items, path, "/MetaData/DataKind").text;
    HeightMapSource source;
    source.reader = "native:opdx";

    if (kind == "Surface Height") {
        const std::string channel = find(items, path, "/MetaData/PrimaryData2D").text;
        const std::string prefix = "/2D_Data/" + channel;
        const std::uint64_t ny = count(path, items, prefix + "/Dimension1Points");
        const std::uint64_t nx = count(path, items, prefix + "/Dimension2Points");
        binary::require_grid_size(path, nx, ny, "OPDx points");
        const Item& matrix = find(items, path, prefix + "/Matrix");
        if (matrix.rows != ny || matrix.columns != nx || matrix.data_bytes != 4 * nx * ny)
            fail("{}: OPDx {}/Matrix holds {} x {} points in {} bytes, the channel states {} x {} (float32: {} bytes)",
                 path, printable(prefix), matrix.columns, matrix.rows, matrix.data_bytes, nx, ny, 4 * nx * ny);
        const double height_um = positive_length_um(path, items, prefix + "/Dimension1Extent");
        const double width_um = positive_length_um(path, items, prefix + "/Dimension2Extent");
        std::vector<double> heights(nx * ny);
        for (std::size_t i = 0; i < heights.size(); ++i) heights[i] = binary::load_f32(bytes.data() + matrix.data_at + 4 * i);
        std::vector<std::uint8_t> valid(heights.size(), 1);
        scale_heights(path, items, prefix, heights, valid, source.height_unit_um);
        HeightMap map(nx, ny, width_um / static_cast<double>(nx), height_um / static_cast<double>(ny), std::move(heights),
                      std::move(valid), path);
        source.format = "Bruker OPDx (.opdx), areal map";
        source.channel = channel;
        map.source = std::move(source);
        return map;
    }
    if (kind == "Surface Profile") {
        const Item& channels = find(items, path, "/MetaData/1D_Channels/Height");
        if (channels.list.empty()) fail("{}: OPDx /MetaData/1D_Channels/Height names no channel", path);
        const std::string prefix = "/1D_Data/" + channels.list.front();
        const std::uint64_t n = count(path, items, prefix + "/NumPoints");
        const Item& array = find(items, path, prefix + "/Array");
        constexpr std::size_t kArrayHead = 5;  // bytes before the doubles
        if (array.data_bytes != kArrayHead + 8 * n)
            fail("{}: OPDx {}/Array holds {} bytes, NumPoints = {} needs {}", path, printable(prefix), array.data_bytes, n,
                 kArrayHead + 8 * n);
        LineScan scan;
        scan.origin = path;
        // Extent runs from the first point to the last (Dektak's text export: x = 0 .. Extent in n - 1 steps).
        if (n < 2) fail("{}: OPDx {}/NumPoints = {}: a profile needs at least 2", path, printable(prefix), n);
        scan.spacing_um = positive_length_um(path, items, prefix + "/Extent") / static_cast<double>(n - 1);
        scan.heights_um.resize(n);
        for (std::size_t i = 0; i < n; ++i) scan.heights_um[i] = binary::load_f64(bytes.data() + array.data_at + kArrayHead + 8 * i);
        scan.validity.assign(n, 1);
        scale_heights(path, items, prefix, scan.heights_um, scan.validity, source.height_unit_um);
        if (scan.valid_count() == scan.size()) scan.validity.clear();
        source.format = "Bruker OPDx (.opdx), stylus profile";
        source.channel = channels.list.front();
        scan.source = std::move(source);
        return scan;
    }
    fail("{}: OPDx data kind '{}' is neither 'Surface Height' nor 'Surface Profile'", path, printable(kind));
}

}  // namespace surfscatter::heightmap
