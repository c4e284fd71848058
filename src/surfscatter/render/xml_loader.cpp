#include "surfscatter/render/xml_loader.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <variant>
#include <vector>

#include <pugixml.hpp>

#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/render/plugins.hpp"
#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::render {

namespace {

namespace fs = std::filesystem;

// One XML file (the scene or an include) with what is needed to turn byte offsets into line numbers.
struct Source {
    fs::path path;
    std::string text;
    std::vector<std::size_t> line_starts;
    pugi::xml_document document;

    // The file name as messages show it (printable: a name may hold any byte).
    std::string shown_path() const { return printable(path.string(), kShownPathChars); }

    int line_of(std::ptrdiff_t offset) const {
        if (offset < 0) return 0;
        const auto it = std::upper_bound(line_starts.begin(), line_starts.end(), static_cast<std::size_t>(offset));
        return static_cast<int>(it - line_starts.begin());
    }
};

// A node together with the file it came from.
struct Node {
    pugi::xml_node xml;
    const Source* source = nullptr;

    std::string where() const {
        std::ptrdiff_t offset = xml.offset_debug();
        // Text is located at its first visible character, not at the line break before it.
        for (const char* c = xml.value(); xml.type() == pugi::node_pcdata && std::isspace(static_cast<unsigned char>(*c)); ++c)
            if (offset >= 0) ++offset;
        return fmt::format("{}:{}", source->shown_path(), source->line_of(offset));
    }
    std::string tag() const { return xml.name(); }
};

// The text of a text node without the whitespace around it, fit for a message.
std::string shown_text(const pugi::xml_node& text) {
    std::string_view value = text.value();
    const auto first = value.find_first_not_of(" \t\r\n"), last = value.find_last_not_of(" \t\r\n");
    return printable(first == std::string_view::npos ? std::string_view() : value.substr(first, last - first + 1));
}

// Errors at an element carry its file:line (SceneError, properties.hpp); `located` adds the location of the element
// being built to any other Error, in one place.
template <typename... Args>
[[noreturn]] void fail_at(const Node& node, fmt::format_string<Args...> format, Args&&... args) {
    throw SceneError(node.where() + ": " + fmt::format(format, std::forward<Args>(args)...));
}

// A plugin that Mitsuba 3 has and surfscatter does not (a volume texture, the hair BSDF): an error like any other,
// except in an object that nothing references, which the loader reports as a note instead (Mitsuba's lego scene
// defines a volume-textured BSDF it never uses).
class UnsupportedPlugin : public SceneError {
public:
    using SceneError::SceneError;
};

// An unknown plugin type of `kind` ("bsdf", "texture"), with the known ones listed in `known`.
[[noreturn]] void unknown_plugin(const Node& node, const std::string& kind, const std::string& type,
                                 const std::string& known) {
    static const std::map<std::string, std::set<std::string>> mitsuba_only = {
        {"bsdf", {"hair", "measured_polarized", "pplastic", "principled", "principledthin", "polarizer",
                  "retarder", "circular"}},
        {"texture", {"mesh_attribute", "volume"}}};
    const auto it = mitsuba_only.find(kind);
    if (it != mitsuba_only.end() && it->second.count(type))
        throw UnsupportedPlugin(fmt::format("{}: unknown {} plugin '{}' ({})", node.where(), kind, type, known));
    fail_at(node, "unknown {} plugin '{}' ({})", kind, printable(type), known);
}

// Mitsuba refuses a second integrator, film, sampler or filter, a shape's second BSDF or emitter: so does this,
// naming both elements.
[[noreturn]] void refuse_second(const Node& first, const Node& second, const std::string& what) {
    fail_at(second, "{} is given twice (the first at {})", what, first.where());
}

// Runs `build`; a library Error without a location is reported at `node`, prefixed by `context` ("bsdf 'ghs': ").
template <typename F>
decltype(auto) located(const Node& node, const std::string& context, F&& build) {
    try {
        return build();
    } catch (const SceneError&) {
        throw;
    } catch (const Error& e) {
        fail_at(node, "{}{}", context, e.what());
    }
}

// Splits an attribute list such as "0, -1.6, 0.9" or "1 0 0": items are separated by commas and/or whitespace, and
// an empty item (",," or a leading or trailing comma) is an error, never skipped.
std::vector<std::string> split_list(const Node& node, const std::string& text, const std::string& what) {
    std::vector<std::string> items;
    const auto is_space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
    if (std::all_of(text.begin(), text.end(), is_space)) return items;
    std::size_t start = 0;
    for (int field = 1;; ++field) {
        const std::size_t comma = text.find(',', start);
        const std::string part = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (std::all_of(part.begin(), part.end(), is_space))
            fail_at(node, "{}: item {} of '{}' is empty", what, field, printable(text));
        for (std::size_t i = 0; i < part.size();) {
            while (i < part.size() && is_space(part[i])) ++i;
            std::size_t j = i;
            while (j < part.size() && !is_space(part[j])) ++j;
            if (j > i) items.push_back(part.substr(i, j - i));
            i = j;
        }
        if (items.size() > kMaxSceneListItems)
            fail_at(node, "{}: more than {} items in one list", what, kMaxSceneListItems);
        if (comma == std::string::npos) return items;
        start = comma + 1;
    }
}

using Object = std::variant<MaterialPtr, TexturePtr>;
using render::Properties;

bool is_parameter_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

class Loader {
public:
    explicit Loader(std::map<std::string, std::string> defines, ParameterSyntax syntax = ParameterSyntax::command_line)
        : syntax_(syntax) {
        // The parameter `model` names the metal's BSDF (scenes/photo-setup, studies): an old spelling of a scattering
        // model's name (-D model=ggx) is read as the name its files and plugins have.
        if (const auto it = defines.find("model"); it != defines.end())
            if (const auto kind = bsdf::find_model(it->second, given("model").c_str())) it->second = bsdf::to_string(*kind);
        defines_ = defines;
        command_line_defines_ = std::move(defines);
    }

    // `used_parameters` null: a -D name the scene never uses is an error; else the names used are added to it.
    std::unique_ptr<Scene> load(const Source& root, std::set<std::string>* used_parameters) {
        scene_ = std::make_unique<Scene>();
        const Node scene_node = root_of(root);
        check_version(scene_node);
        load_children(scene_node);
        build_unreferenced();
        if (!sensor_) fail_at(scene_node, "the scene has no <sensor>");
        located(scene_node, "", [&] { scene_->commit(); });
        if (used_parameters) {
            used_parameters->insert(used_defines_.begin(), used_defines_.end());
        } else {
            for (const auto& [name, value] : command_line_defines_)
                if (!used_defines_.count(name))
                    fail("{}={}: the scene {} never uses ${} (a misspelt parameter would be silently ignored)",
                         given(name), printable(value), root.shown_path(), name);
        }
        return std::move(scene_);
    }

private:
    // A parameter as the caller passes it.
    std::string given(const std::string& name) const {
        return syntax_ == ParameterSyntax::python ? fmt::format("params['{}']", name) : "-D " + name;
    }

    // ---------------------------------------------------------------- attributes and values

    std::string attribute(const Node& node, const char* name, bool required = true) {
        const pugi::xml_attribute attr = node.xml.attribute(name);
        if (!attr) {
            if (required) fail_at(node, "<{}> needs the attribute '{}'", node.tag(), name);
            return {};
        }
        return substitute(node, attr.value());
    }

    std::string substitute(const Node& node, const std::string& text) {
        std::string out;
        for (std::size_t i = 0; i < text.size();) {
            if (text[i] != '$') {
                out += text[i++];
                continue;
            }
            std::size_t j = i + 1;
            while (j < text.size() && is_parameter_char(text[j])) ++j;
            const std::string name = text.substr(i + 1, j - i - 1);
            if (name.empty()) fail_at(node, "'$' without a parameter name in '{}'", printable(text));
            const auto it = defines_.find(name);
            if (it == defines_.end())
                fail_at(node, "parameter ${} is not defined (pass {}=... or add <default name=\"{}\" .../>)", name,
                        given(name), name);
            used_defines_.insert(name);
            out += it->second;
            i = j;
        }
        return out;
    }

    static void check_attributes(const Node& node, std::initializer_list<const char*> allowed) {
        for (const auto& attr : node.xml.attributes()) {
            const bool ok = std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return std::string(a) == attr.name(); });
            if (!ok) fail_at(node, "unknown attribute '{}' of <{}>", printable(attr.name()), node.tag());
        }
    }

    // A value element (<float>, <translate>, <default>, ...): its attributes only, no text and no child elements.
    static void check_leaf(const Node& node, std::initializer_list<const char*> allowed) {
        check_attributes(node, allowed);
        for (pugi::xml_node child : node.xml.children()) {
            if (child.type() == pugi::node_comment) continue;
            const Node c{child, node.source};
            if (child.type() == pugi::node_element) fail_at(c, "<{}> cannot contain elements, got <{}>", node.tag(), c.tag());
            fail_at(c, "<{}> cannot contain text, got '{}' (values go in attributes)", node.tag(), shown_text(child));
        }
    }

    // Text between the elements of a plugin or transform would be silently dropped: refuse it.
    static void check_no_text(const Node& node) {
        for (pugi::xml_node child : node.xml.children())
            if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata)
                fail_at(Node{child, node.source}, "unexpected text '{}' inside <{}>", shown_text(child), node.tag());
    }

    static double parse_double(const Node& node, const std::string& text, const std::string& what) {
        const char* begin = text.c_str();
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(begin, &end);
        // ERANGE on underflow still gives the nearest double (a denormal or 0): keep it; overflow is not finite.
        const bool whole = end != begin && end == begin + text.size() && !std::isspace(static_cast<unsigned char>(text[0]));
        if (!whole || !std::isfinite(v) || (errno == ERANGE && std::abs(v) > 1.0))
            fail_at(node, "{}: '{}' is not a finite number", what, printable(text));
        return v;
    }

    static std::vector<double> parse_list(const Node& node, const std::string& text, const std::string& what) {
        std::vector<double> values;
        for (const std::string& item : split_list(node, text, what)) values.push_back(parse_double(node, item, what));
        return values;
    }

    Vec3 parse_xyz(const Node& node, double fallback) {
        if (node.xml.attribute("value")) {
            const auto v = parse_list(node, attribute(node, "value"), node.tag());
            if (v.size() == 1) return {v[0], v[0], v[0]};
            if (v.size() != 3) fail_at(node, "<{}> value needs 1 or 3 numbers", node.tag());
            return {v[0], v[1], v[2]};
        }
        Vec3 out(fallback, fallback, fallback);
        const char* names[3] = {"x", "y", "z"};
        for (int c = 0; c < 3; ++c)
            if (node.xml.attribute(names[c])) out[c] = parse_double(node, attribute(node, names[c]), names[c]);
        return out;
    }

    // ---------------------------------------------------------------- property lists

    struct Property {
        Node node;
        bool used = false;
    };

    // The children of a plugin element: named parameters, plus unnamed nested objects.
    class ElementProperties final : public Properties {
    public:
        ElementProperties(Loader& loader, const Node& owner) : loader_(loader), owner_(owner) {
            check_no_text(owner);
            for (pugi::xml_node child : owner.xml.children()) {
                if (child.type() != pugi::node_element) continue;
                const Node node{child, owner.source};
                const std::string name = child.attribute("name") ? loader.substitute(node, child.attribute("name").value()) : "";
                // Nested objects may carry names (Mitsuba ignores them); they are taken by kind. A named <ref> to
                // anything but a texture (<ref id="mat" name="bsdf"/>) is a nested BSDF.
                if (name.empty() || loader.is_bsdf(node)) {
                    unnamed_.push_back({node});
                    continue;
                }
                if (named_.count(name)) render::fail_at(node, "parameter '{}' given twice", printable(name));
                named_.emplace(name, Property{node});
            }
        }

        std::string where() const override { return owner_.where(); }
        std::string where(const std::string& name) const override {
            const auto it = named_.find(name);
            return it == named_.end() ? owner_.where() : it->second.node.where();
        }

        const Node* find(const std::string& name) {
            auto it = named_.find(name);
            if (it == named_.end()) return nullptr;
            it->second.used = true;
            return &it->second.node;
        }

        const Node* find_typed(const std::string& name, const char* tag) {
            const Node* node = find(name);
            if (node && node->tag() != tag) render::fail_at(*node, "parameter '{}' must be a <{}>, got <{}>", name, tag, node->tag());
            return node;
        }

        double get_float(const std::string& name, double fallback) override {
            const Node* node = find(name);
            if (!node) return fallback;
            if (node->tag() != "float" && node->tag() != "integer")
                render::fail_at(*node, "parameter '{}' must be a <float>, got <{}>", name, node->tag());
            check_leaf(*node, {"name", "value"});
            return loader_.parse_double(*node, loader_.attribute(*node, "value"), name);
        }
        double get_float_required(const std::string& name) override {
            if (!named_.count(name)) render::fail_at(owner_, "<{}> needs the parameter '{}'", owner_.tag(), name);
            return get_float(name, 0);
        }
        int get_int(const std::string& name, int fallback) override {
            const Node* node = find_typed(name, "integer");
            if (!node) return fallback;
            check_leaf(*node, {"name", "value"});
            const double v = loader_.parse_double(*node, loader_.attribute(*node, "value"), name);
            if (v != std::floor(v) || std::abs(v) > 2e9) render::fail_at(*node, "{}: '{}' is not an integer", name, v);
            return static_cast<int>(v);
        }
        bool get_bool(const std::string& name, bool fallback) override {
            const Node* node = find_typed(name, "boolean");
            if (!node) return fallback;
            check_leaf(*node, {"name", "value"});
            const std::string v = loader_.attribute(*node, "value");
            if (v == "true") return true;
            if (v == "false") return false;
            render::fail_at(*node, "{}: boolean must be true or false, got '{}'", name, v);
        }
        std::string get_string(const std::string& name, const std::string& fallback) override {
            const Node* node = find_typed(name, "string");
            if (!node) return fallback;
            check_leaf(*node, {"name", "value"});
            return loader_.attribute(*node, "value");
        }
        std::optional<std::variant<double, std::string>> get_float_or_string(const std::string& name) override {
            const Node* node = find(name);
            if (!node) return std::nullopt;
            if (node->tag() != "float" && node->tag() != "string")
                render::fail_at(*node, "parameter '{}' must be a <float> or a <string>, got <{}>", name, node->tag());
            check_leaf(*node, {"name", "value"});
            const std::string value = loader_.attribute(*node, "value");
            if (node->tag() == "float") return loader_.parse_double(*node, value, name);
            return value;
        }
        std::optional<Vec3> get_point(const std::string& name) override {
            const Node* node = find(name);
            if (!node) return std::nullopt;
            if (node->tag() != "point" && node->tag() != "vector")
                render::fail_at(*node, "parameter '{}' must be a <point>, got <{}>", name, node->tag());
            check_leaf(*node, {"name", "value", "x", "y", "z"});
            const Vec3 p = loader_.parse_xyz(*node, 0.0);
            for (int c = 0; c < 3; ++c)
                if (!(std::abs(p[c]) <= kMaxSceneCoordinate))
                    render::fail_at(*node, "{}: {} is beyond the +-{:g} a scene may span", name, p[c], kMaxSceneCoordinate);
            return p;
        }
        Transform get_transform(const std::string& name) override {
            const Node* node = find_typed(name, "transform");
            return node ? loader_.build_transform(*node) : Transform();
        }
        fs::path get_file(const std::string& name) override {
            const Node* node = find_typed(name, "string");
            if (!node) render::fail_at(owner_, "<{}> needs the parameter '{}'", owner_.tag(), name);
            check_leaf(*node, {"name", "value"});
            return loader_.resolve(*node, loader_.attribute(*node, "value"));
        }
        TexturePtr get_texture(const std::string& name, double fallback) override {
            const Node* node = find(name);
            return node ? loader_.build_texture_param(*node) : make_constant_texture(make_constant_spectrum(fallback));
        }
        TexturePtr get_texture_required(const std::string& name) override {
            const Node* node = find(name);
            if (!node) render::fail_at(owner_, "<{}> needs the parameter '{}'", owner_.tag(), name);
            return loader_.build_texture_param(*node);
        }
        SpectrumPtr get_spectrum(const std::string& name, bool illuminant, std::optional<double> fallback) override {
            const Node* node = find(name);
            if (!node) {
                if (!fallback) render::fail_at(owner_, "<{}> needs the parameter '{}'", owner_.tag(), name);
                return illuminant ? make_d65_illuminant(*fallback) : make_constant_spectrum(*fallback);
            }
            return loader_.build_spectrum(*node, illuminant);
        }
        std::vector<MaterialPtr> take_bsdfs() override {
            std::vector<MaterialPtr> out;
            for (Property& p : unnamed_) {
                if (p.used) continue;
                if (loader_.is_bsdf(p.node)) {
                    p.used = true;
                    out.push_back(loader_.build_bsdf(p.node));
                }
            }
            return out;
        }
        std::vector<TexturePtr> take_textures() override {
            std::vector<TexturePtr> out;
            auto take = [&](Property& p) {
                const bool texture_ref = p.node.tag() == "ref" && loader_.names_texture(p.node);
                if (p.used || (p.node.tag() != "texture" && !texture_ref)) return;
                p.used = true;
                out.push_back(loader_.build_texture_param(p.node));
            };
            for (Property& p : unnamed_) take(p);
            for (auto& [name, p] : named_) take(p);
            return out;
        }
        bool has(const std::string& name) const override { return named_.count(name) != 0; }
        void share_height_map(bsdf::SurfaceOptions& surface) override { loader_.share_height_map(surface); }
        void add_note(const std::string& note) override { loader_.scene_->notes.push_back(owner_.where() + ": " + note); }

        // The nested BSDFs not taken yet, as take_bsdfs will find them.
        std::vector<Node> bsdf_nodes() {
            std::vector<Node> out;
            for (const Property& p : unnamed_)
                if (!p.used && loader_.is_bsdf(p.node))
                    out.push_back(p.node);
            return out;
        }

        // Unnamed nested objects of a kind (<emitter>, <film>, ...).
        std::vector<Node> take_unnamed(const char* tag) {
            std::vector<Node> out;
            for (Property& p : unnamed_) {
                if (p.used) continue;
                if (p.node.tag() == tag) {
                    p.used = true;
                    out.push_back(p.node);
                }
            }
            return out;
        }
        void check_all_used(const std::string& plugin) {
            for (auto& [name, p] : named_)
                if (!p.used) render::fail_at(p.node, "unknown parameter '{}' of {} (<{}>)", printable(name), plugin, p.node.tag());
            for (const Property& p : unnamed_)
                if (!p.used) render::fail_at(p.node, "unexpected <{}> inside {}", printable(p.node.tag()), plugin);
        }

    private:
        Loader& loader_;
        Node owner_;
        std::map<std::string, Property> named_;
        std::vector<Property> unnamed_;
    };

    // ---------------------------------------------------------------- transforms

    Transform build_transform(const Node& node) {
        check_attributes(node, {"name"});
        check_no_text(node);
        Transform t;
        for (pugi::xml_node child : node.xml.children()) {
            if (child.type() != pugi::node_element) continue;
            const Node c{child, node.source};
            const std::string tag = c.tag();
            Transform op;
            try {
                if (tag == "translate") {
                    check_leaf(c, {"value", "x", "y", "z"});
                    op = Transform::translate(parse_xyz(c, 0.0));
                } else if (tag == "scale") {
                    check_leaf(c, {"value", "x", "y", "z"});
                    op = Transform::scale(parse_xyz(c, 1.0));
                } else if (tag == "rotate") {
                    check_leaf(c, {"value", "x", "y", "z", "angle"});
                    const Vec3 axis = parse_xyz(c, 0.0);
                    op = Transform::rotate(axis, parse_double(c, attribute(c, "angle"), "angle"));
                } else if (tag == "matrix") {
                    check_leaf(c, {"value"});
                    const auto v = parse_list(c, attribute(c, "value"), "matrix");
                    if (v.size() != 16 && v.size() != 9) fail_at(c, "<matrix> needs 16 (or 9) numbers, got {}", v.size());
                    std::array<double, 16> m{};
                    if (v.size() == 16) std::copy(v.begin(), v.end(), m.begin());
                    else {
                        for (int r = 0; r < 3; ++r)
                            for (int k = 0; k < 3; ++k) m[static_cast<std::size_t>(4 * r + k)] = v[static_cast<std::size_t>(3 * r + k)];
                        m[15] = 1;
                    }
                    op = Transform::from_rows(m);
                } else if (tag == "lookat") {
                    check_leaf(c, {"origin", "target", "up"});
                    auto vec = [&](const char* a) {
                        const auto v = parse_list(c, attribute(c, a), a);
                        if (v.size() != 3) fail_at(c, "lookat {} needs 3 numbers", a);
                        return Vec3(v[0], v[1], v[2]);
                    };
                    const Vec3 up = c.xml.attribute("up") ? vec("up") : Vec3(0, 1, 0);
                    op = Transform::look_at(vec("origin"), vec("target"), up);
                } else {
                    fail_at(c, "unknown transform operation <{}>", printable(tag));
                }
            } catch (const SceneError&) {
                throw;
            } catch (const Error& e) {
                fail_at(c, "{}", e.what());
            }
            t = op * t;  // later operations apply after earlier ones (Mitsuba)
            for (const auto& row : t.m)
                for (double x : row)
                    if (!std::isfinite(x) || std::abs(x) > kMaxSceneCoordinate)
                        fail_at(c, "the transform reaches {} (beyond the +-{:g} a scene may span)", x,
                                kMaxSceneCoordinate);
        }
        return t;
    }

    // ---------------------------------------------------------------- spectra and textures

    // Mitsuba's spectral variants multiply an emitter's constant value by the D65 illuminant (normalised to Y = 1).
    static SpectrumPtr make_d65_illuminant(double value) {
        if (!(value >= 0 && value <= kMaxSpectrumValue))
            fail("spectrum value must be between 0 and {:g}, got {}", kMaxSpectrumValue, value);
        return make_rgb_illuminant({value, value, value});
    }

    // float, <spectrum>, <rgb> -> a spectrum; `illuminant` selects the emission variant (RGB and constants times
    // D65, as Mitsuba's spectral variants do for emitters).
    SpectrumPtr build_spectrum(const Node& node, bool illuminant) {
        const std::string tag = node.tag();
        try {
            if (tag == "float") {
                check_leaf(node, {"name", "value"});
                const double v = parse_double(node, attribute(node, "value"), "value");
                return illuminant ? make_d65_illuminant(v) : make_constant_spectrum(v);
            }
            if (tag == "rgb") {
                check_leaf(node, {"name", "value"});
                const auto v = parse_list(node, attribute(node, "value"), "rgb");
                if (v.size() != 1 && v.size() != 3) fail_at(node, "<rgb> needs 1 or 3 numbers, got {}", v.size());
                const std::array<double, 3> rgb = v.size() == 1 ? std::array<double, 3>{v[0], v[0], v[0]}
                                                                : std::array<double, 3>{v[0], v[1], v[2]};
                for (double x : rgb)
                    if (x < 0) fail_at(node, "<rgb> values must be non-negative, got {}", x);
                return illuminant ? make_rgb_illuminant(rgb) : make_rgb_reflectance(rgb);
            }
            if (tag == "spectrum") return build_spectrum_element(node, illuminant);
        } catch (const SceneError&) {
            throw;
        } catch (const Error& e) {
            fail_at(node, "{}", e.what());
        }
        fail_at(node, "expected <float>, <spectrum> or <rgb>, got <{}>", printable(tag));
    }

    // <spectrum value="0.5"/>, value="400:0.1, 500:0.3, ..." (piecewise linear), filename="x.spd" (Mitsuba's
    // "wavelength value" lines, # comments), type="blackbody" (temperature, scale), type="d65" (scale).
    SpectrumPtr build_spectrum_element(const Node& node, bool illuminant) {
        const std::string type = node.xml.attribute("type") ? attribute(node, "type") : "";
        if (type == "blackbody" || type == "d65") {
            check_attributes(node, {"name", "type"});
            ElementProperties props(*this, node);
            const double scale = props.get_float("scale", 1.0);
            SpectrumPtr s;
            if (type == "blackbody") {
                const double temperature = props.get_float_required("temperature");
                s = make_blackbody_spectrum(temperature, scale);
            } else {
                s = make_d65_illuminant(scale);
            }
            props.check_all_used("spectrum '" + type + "'");
            return s;
        }
        if (!type.empty())
            fail_at(node, "unknown spectrum type '{}' (a value, a value list, filename, blackbody, d65)", printable(type));
        check_leaf(node, {"name", "value", "filename"});
        std::vector<double> lambdas, values;
        if (node.xml.attribute("filename")) {
            if (node.xml.attribute("value")) fail_at(node, "<spectrum> takes either value or filename, not both");
            const fs::path path = resolve(node, attribute(node, "filename"));
            const std::string text = located(node, "", [&] { return read_input_file(path, "spectrum file"); });
            int number = 0;
            for (std::size_t start = 0; start < text.size();) {
                const std::size_t end = std::min(text.find('\n', start), text.size());
                std::string line = text.substr(start, end - start);
                start = end + 1;
                ++number;
                const auto hash = line.find('#');
                if (hash != std::string::npos) line.resize(hash);
                std::vector<std::string> words;
                for (std::size_t i = 0; i < line.size();) {
                    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
                    std::size_t j = i;
                    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
                    if (j > i) words.push_back(line.substr(i, j - i));
                    i = j;
                }
                if (words.empty()) continue;  // blank or comment line
                const std::string where = fmt::format("{}:{}", printable(path.string(), kShownPathChars), number);
                if (words.size() != 2) fail_at(node, "{}: expected 'wavelength value', got '{}'", where, printable(line));
                lambdas.push_back(parse_double(node, words[0], where + ": wavelength"));
                values.push_back(parse_double(node, words[1], where + ": value"));
            }
        } else {
            const std::string value = attribute(node, "value");
            if (value.find(':') == std::string::npos) {
                const double v = parse_double(node, value, "spectrum value");
                return illuminant ? make_d65_illuminant(v) : make_constant_spectrum(v);
            }
            for (const std::string& pair : split_list(node, value, "spectrum")) {
                const auto colon = pair.find(':');
                if (colon == std::string::npos) fail_at(node, "spectrum entry '{}' is not lambda:value", printable(pair));
                lambdas.push_back(parse_double(node, pair.substr(0, colon), "wavelength"));
                values.push_back(parse_double(node, pair.substr(colon + 1), "spectrum value"));
            }
        }
        return make_tabulated_spectrum(lambdas, values);
    }

    TexturePtr build_texture_param(const Node& node) {
        const std::string tag = node.tag();
        if (tag == "texture") return build_texture(node);
        if (tag == "ref") return std::get<TexturePtr>(lookup(node, "texture"));
        return make_constant_texture(build_spectrum(node, false));
    }

    TexturePtr build_texture(const Node& node) {
        check_attributes(node, {"type", "name", "id"});
        const std::string type = attribute(node, "type");
        using Factory = TexturePtr (*)(Properties&);
        static const std::map<std::string, Factory> factories = {{"bitmap", plugins::bitmap},
                                                                  {"checkerboard", plugins::checkerboard}};
        const auto it = factories.find(type);
        if (it == factories.end()) unknown_plugin(node, "texture", type, "bitmap, checkerboard");
        ElementProperties props(*this, node);
        TexturePtr texture = build(node, "texture '" + type + "'", [&] { return it->second(props); });
        props.check_all_used("texture '" + type + "'");
        register_id(node, texture);
        return texture;
    }

    // Runs a plugin factory; an error without a file:line gets the element's.
    template <typename Build>
    auto build(const Node& node, const std::string& plugin, Build&& build_object) -> decltype(build_object()) {
        return located(node, plugin + ": ", build_object);
    }

    // Each surface_file is read and prepared once per scene and preparation (several BSDFs may use it) and reported in
    // the scene's notes. A profile (line scan) is read by each BSDF that names it, and noted by make_bsdf.
    void share_height_map(bsdf::SurfaceOptions& surface) {
        if (surface.psd != bsdf::PsdKind::file && surface.psd != bsdf::PsdKind::measured) return;
        std::shared_ptr<const heightmap::PreparedMap>& shared = height_maps_[{surface.surface_file, surface.preparation}];
        if (!shared) {
            bsdf::load_height_map(surface);
            if (surface.profile) return;
            shared = surface.prepared;
            std::string note = heightmap::describe(shared->map);
            for (const std::string& line : bsdf::preparation_notes(surface)) note += "; " + line;
            scene_->notes.push_back(std::move(note));
        }
        surface.prepared = shared;
        surface.preparation_noted = true;  // in the map's note above, once
    }

    // ---------------------------------------------------------------- BSDFs

    MaterialPtr build_bsdf(const Node& node) {
        if (node.tag() == "ref") return std::get<MaterialPtr>(lookup(node, "bsdf"));
        check_attributes(node, {"type", "id", "name"});
        const std::string type = attribute(node, "type");
        using Factory = MaterialPtr (*)(Properties&);
        static const std::map<std::string, Factory> factories = {
            {"diffuse", plugins::diffuse},         {"conductor", plugins::conductor},
            {"roughconductor", plugins::roughconductor}, {"dielectric", plugins::dielectric},
            {"thindielectric", plugins::thindielectric}, {"roughdielectric", plugins::roughdielectric},
            {"plastic", plugins::plastic},         {"roughplastic", plugins::roughplastic},
            {"twosided", plugins::twosided},       {"blendbsdf", plugins::blendbsdf},
            {"mask", plugins::mask},               {"bumpmap", plugins::bumpmap},
            {"normalmap", plugins::normalmap},     {"measured", plugins::measured}};
        const auto it = factories.find(type);
        // A scattering model is built under its canonical name (an old spelling is reported once, here).
        std::optional<bsdf::ModelKind> model;
        if (it == factories.end()) model = bsdf::find_model(type, (node.where() + ": bsdf type").c_str());
        if (!model && it == factories.end())
            unknown_plugin(node, "bsdf", type, "diffuse, conductor, roughconductor, dielectric, thindielectric, "
                                               "roughdielectric, plastic, roughplastic, twosided, blendbsdf, mask, "
                                               "bumpmap, normalmap, measured, " + bsdf::choices("model"));
        const std::string plugin = model ? bsdf::to_string(*model) : type;
        ElementProperties props(*this, node);
        MaterialPtr material = build(node, "bsdf '" + plugin + "'", [&] {
            return model ? plugins::scattering_model(props, plugin) : it->second(props);
        });
        props.check_all_used("bsdf '" + plugin + "'");
        register_id(node, material);
        return material;
    }

    // ---------------------------------------------------------------- shapes, emitters, sensor

    void build_shape(const Node& node) {
        check_attributes(node, {"type", "id"});
        const std::string type = attribute(node, "type");
        using Factory = ShapeGeometry (*)(Properties&);
        static const std::map<std::string, Factory> factories = {
            {"obj", plugins::obj},   {"ply", plugins::ply},       {"serialized", plugins::serialized},
            {"rectangle", plugins::rectangle}, {"disk", plugins::disk}, {"cube", plugins::cube},
            {"sphere", plugins::sphere}, {"cylinder", plugins::cylinder}};
        const auto it = factories.find(type);
        if (it == factories.end())
            fail_at(node, "unknown shape plugin '{}' (obj, ply, serialized, rectangle, disk, cube, sphere, cylinder)",
                    printable(type));
        register_name(node);
        ElementProperties props(*this, node);
        if (const std::vector<Node> nodes = props.bsdf_nodes(); nodes.size() > 1)
            refuse_second(nodes[0], nodes[1], "a shape's <bsdf>");
        std::vector<MaterialPtr> bsdfs = props.take_bsdfs();
        SpectrumPtr radiance;
        const std::vector<Node> emitters = props.take_unnamed("emitter");
        if (emitters.size() > 1) refuse_second(emitters[0], emitters[1], "a shape's <emitter>");
        if (!emitters.empty()) {
            const Node& e = emitters[0];
            check_attributes(e, {"type", "id", "name"});
            if (attribute(e, "type") != "area")
                fail_at(e, "a shape's emitter must be of type 'area', got '{}'", printable(attribute(e, "type")));
            ElementProperties eprops(*this, e);
            radiance = plugins::area(eprops);
            eprops.check_all_used("emitter 'area'");
        }
        MaterialPtr material = bsdfs.empty() ? nullptr : bsdfs[0];
        if (!material && !radiance) material = make_diffuse(make_constant_texture(make_constant_spectrum(0.5)));  // Mitsuba's default
        ShapeGeometry geometry = build(node, "shape '" + type + "'", [&] { return it->second(props); });
        props.check_all_used("shape '" + type + "'");
        build(node, "shape '" + type + "'", [&] {
            scene_->add_shape(std::move(geometry), material, radiance);
            return 0;
        });
    }

    void build_emitter(const Node& node) {
        check_attributes(node, {"type", "id"});
        const std::string type = attribute(node, "type");
        if (type == "area") fail_at(node, "an area emitter must be nested in a <shape>");
        using Factory = EmitterPtr (*)(Properties&);
        static const std::map<std::string, Factory> factories = {
            {"point", plugins::point}, {"spot", plugins::spot}, {"directional", plugins::directional},
            {"constant", plugins::constant}, {"envmap", plugins::envmap}};
        const auto it = factories.find(type);
        if (it == factories.end())
            fail_at(node, "unknown emitter plugin '{}' (point, spot, directional, area, constant, envmap)", printable(type));
        register_name(node);
        ElementProperties props(*this, node);
        EmitterPtr emitter = build(node, "emitter '" + type + "'", [&] { return it->second(props); });
        props.check_all_used("emitter '" + type + "'");
        scene_->add_emitter(std::move(emitter));
    }

    void build_sensor(const Node& node) {
        check_attributes(node, {"type", "id"});
        const std::string type = attribute(node, "type");
        if (type != "perspective" && type != "thinlens")
            fail_at(node, "unknown sensor plugin '{}' (perspective, thinlens)", printable(type));
        if (sensor_) fail_at(node, "only one <sensor> is supported (the first is at {})", sensor_->where());
        sensor_ = node;
        register_name(node);
        ElementProperties props(*this, node);
        // The film first: its size sets the field of view's axes.
        const std::vector<Node> films = props.take_unnamed("film");
        if (films.size() > 1) refuse_second(films[0], films[1], "a sensor's <film>");
        if (!films.empty()) build_film(films[0]);
        const std::vector<Node> samplers = props.take_unnamed("sampler");
        if (samplers.size() > 1) refuse_second(samplers[0], samplers[1], "a sensor's <sampler>");
        if (!samplers.empty()) build_sampler(samplers[0]);
        const int w = scene_->film.width, h = scene_->film.height;
        scene_->camera = build(node, "sensor '" + type + "'", [&] {
            return type == "perspective" ? plugins::perspective(props, w, h) : plugins::thinlens(props, w, h);
        });
        props.check_all_used("sensor '" + type + "'");
    }

    void build_film(const Node& node) {
        check_attributes(node, {"type", "id", "name"});
        const std::string type = attribute(node, "type");
        if (type != "hdrfilm") fail_at(node, "unknown film plugin '{}' (hdrfilm)", printable(type));
        ElementProperties props(*this, node);
        FilterPtr filter = make_gaussian_filter();
        const std::vector<Node> filters = props.take_unnamed("rfilter");
        if (filters.size() > 1) refuse_second(filters[0], filters[1], "a film's <rfilter>");
        if (!filters.empty()) filter = build_filter(filters[0]);
        scene_->film = build(node, "film 'hdrfilm'", [&] { return plugins::hdrfilm(props, filter); });
        props.check_all_used("film 'hdrfilm'");
    }

    FilterPtr build_filter(const Node& node) {
        check_attributes(node, {"type", "name", "id"});
        const std::string type = attribute(node, "type");
        using Factory = FilterPtr (*)(Properties&);
        static const std::map<std::string, Factory> factories = {
            {"box", plugins::box},           {"tent", plugins::tent},         {"gaussian", plugins::gaussian},
            {"mitchell", plugins::mitchell}, {"catmullrom", plugins::catmullrom}, {"lanczos", plugins::lanczos}};
        const auto it = factories.find(type);
        if (it == factories.end())
            fail_at(node, "unknown rfilter plugin '{}' (box, tent, gaussian, mitchell, catmullrom, lanczos)", printable(type));
        ElementProperties props(*this, node);
        FilterPtr filter = build(node, "rfilter '" + type + "'", [&] { return it->second(props); });
        props.check_all_used("rfilter '" + type + "'");
        return filter;
    }

    void build_sampler(const Node& node) {
        check_attributes(node, {"type", "id", "name"});
        const std::string type = attribute(node, "type");
        if (type != "independent") fail_at(node, "unknown sampler plugin '{}' (independent)", printable(type));
        ElementProperties props(*this, node);
        scene_->sampler.sample_count = props.get_int("sample_count", scene_->sampler.sample_count);
        if (scene_->sampler.sample_count <= 0) fail_at(node, "sample_count must be positive");
        const int seed = props.get_int("seed", 0);
        if (seed < 0) fail_at(node, "seed must be non-negative, got {}", seed);
        scene_->sampler.seed = static_cast<std::uint64_t>(seed);
        props.check_all_used("sampler 'independent'");
    }

    void build_integrator(const Node& node) {
        check_attributes(node, {"type", "id"});
        const std::string type = attribute(node, "type");
        if (type == "aov")
            fail_at(node, "integrator 'aov' is not supported: surfscatter renders radiance only (use path or direct)");
        if (type != "path" && type != "direct") fail_at(node, "unknown integrator plugin '{}' (path, direct)", printable(type));
        if (integrator_) refuse_second(*integrator_, node, "<integrator>");
        integrator_ = node;
        ElementProperties props(*this, node);
        scene_->integrator = build(node, "integrator '" + type + "'", [&] {
            return type == "path" ? plugins::path(props) : plugins::direct(props);
        });
        props.check_all_used("integrator '" + type + "'");
    }

    // ---------------------------------------------------------------- scene level

    void load_children(const Node& scene_node) {
        for (pugi::xml_node child : scene_node.xml.children()) {
            if (child.type() != pugi::node_element) continue;
            const Node node{child, scene_node.source};
            const std::string tag = node.tag();
            if (tag == "default") {
                check_leaf(node, {"name", "value"});
                const std::string name = node.xml.attribute("name").value();
                if (name.empty()) fail_at(node, "<default> needs a name");
                if (!node.xml.attribute("value")) fail_at(node, "<default> needs a value");
                const std::string value = node.xml.attribute("value").value();
                const auto [first, added] = defaults_.emplace(name, node);
                if (!added && first->second.xml.attribute("value").value() != value)
                    fail_at(node, "<default name=\"{}\"> is given twice with different values ('{}' here, '{}' at {})",
                            printable(name), printable(value), printable(first->second.xml.attribute("value").value()),
                            first->second.where());
                defines_.emplace(name, value);  // -D values win
            } else if (tag == "include") {
                check_leaf(node, {"filename"});
                const fs::path path = resolve_include(node);
                if (++include_depth_ > kMaxIncludeDepth)
                    fail_at(node, "includes nested more than {} deep (a cycle?)", kMaxIncludeDepth);
                if (++include_count_ > kMaxIncludes) fail_at(node, "more than {} <include>s in one scene", kMaxIncludes);
                const Node root = root_of(open(path, &node));
                check_version(root);
                load_children(root);
                --include_depth_;
            } else if (tag == "integrator") {
                build_integrator(node);
            } else if (tag == "sensor") {
                build_sensor(node);
            } else if (tag == "shape") {
                build_shape(node);
            } else if (tag == "emitter") {
                build_emitter(node);
            } else if (tag == "bsdf" || tag == "texture") {
                // Built when first referenced (it may refer to objects defined after it); those that nothing
                // references are built after the whole scene is read (build_unreferenced).
                if (!node.xml.attribute("id")) fail_at(node, "a top-level <{}> needs an id", tag);
                const std::string id = attribute(node, "id");
                if (objects_.count(id) || names_.count(id) || !pending_.emplace(id, node).second)
                    fail_at(node, "duplicate id '{}'", printable(id));
                pending_order_.push_back(id);
            } else {
                fail_at(node, "unknown element <{}> in <scene>", printable(tag));
            }
        }
    }

    // The <scene> element of a file: the one element at the top, with nothing but comments beside it.
    static Node root_of(const Source& source) {
        Node root{pugi::xml_node(), &source};
        for (pugi::xml_node child : source.document.children()) {
            const Node c{child, &source};
            if (child.type() == pugi::node_comment || child.type() == pugi::node_declaration ||
                child.type() == pugi::node_doctype || child.type() == pugi::node_pi)
                continue;
            if (child.type() != pugi::node_element) fail_at(c, "unexpected text '{}' outside <scene>", shown_text(child));
            if (root.xml) fail_at(c, "a second root element <{}> (a file holds one <scene>)", printable(c.tag()));
            if (c.tag() != "scene") fail_at(c, "the root element must be <scene>, got <{}>", printable(c.tag()));
            root.xml = child;
        }
        if (!root.xml) fail("{}:1: the file has no <scene> element", source.shown_path());
        check_no_text(root);
        return root;
    }

    // An <include> named by a parameter (filename="metal_$model.xml") that names no file is an error listing the
    // values that would, from the files beside it.
    fs::path resolve_include(const Node& node) {
        const std::string raw = node.xml.attribute("filename").value();
        const std::string filename = attribute(node, "filename");
        const std::size_t dollar = raw.find('$');
        std::size_t end = dollar + 1;
        while (dollar != std::string::npos && end < raw.size() && is_parameter_char(raw[end])) ++end;
        fs::path p(filename);
        if (p.is_relative()) p = node.source->path.parent_path() / p;
        if (dollar == std::string::npos || raw.find('$', end) != std::string::npos || fs::exists(p))
            return resolve(node, filename);
        const std::string name = raw.substr(dollar + 1, end - dollar - 1);
        const fs::path prefix = node.source->path.parent_path() / raw.substr(0, dollar);
        const std::string stem = prefix.filename().string(), suffix = raw.substr(end);
        std::set<std::string> values;
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(prefix.parent_path(), ec)) {
            const std::string file = entry.path().filename().string();
            if (file.size() > stem.size() + suffix.size() && file.starts_with(stem) && file.ends_with(suffix))
                values.insert(file.substr(stem.size(), file.size() - stem.size() - suffix.size()));
        }
        if (values.empty())
            fail_at(node, "file not found: {} (from {}={})", p.string(), name, printable(defines_.at(name)));
        fail_at(node, "{}={} names no file ({} not found): {} must be one of {}", name, printable(defines_.at(name)),
                p.filename().string(), name, fmt::join(values, " | "));
    }

    fs::path resolve(const Node& node, const std::string& filename) {
        fs::path p(filename);
        if (p.is_relative()) p = node.source->path.parent_path() / p;
        located(node, "", [&] { require_readable_file(p, "file"); });
        const std::string label = node.xml.attribute("name") ? node.xml.attribute("name").value() : "<" + node.tag() + ">";
        scene_->loaded_files.push_back({p, fmt::format("{} at {}", printable(label), node.where())});
        return p;
    }

    void register_id(const Node& node, Object object) {
        if (!node.xml.attribute("id")) return;
        const std::string id = attribute(node, "id");
        if (names_.count(id) || (!pending_.count(id) && objects_.count(id)) || !objects_.emplace(id, std::move(object)).second)
            fail_at(node, "duplicate id '{}'", printable(id));
    }

    // Shapes, emitters and sensors may carry an id (a name only: nothing refers to them).
    void register_name(const Node& node) {
        if (!node.xml.attribute("id")) return;
        const std::string id = attribute(node, "id");
        if (objects_.count(id) || pending_.count(id) || !names_.insert(id).second)
            fail_at(node, "duplicate id '{}'", printable(id));
    }

    // A top-level object defined earlier and not built yet: build it now (once; a cycle of references is an error).
    void build_pending(const Node& ref, const std::string& id) {
        const auto it = pending_.find(id);
        if (it == pending_.end()) return;
        if (!building_.insert(id).second) fail_at(ref, "reference cycle through id '{}'", printable(id));
        const Node node = it->second;
        if (node.tag() == "bsdf") build_bsdf(node);
        else build_texture(node);
        building_.erase(id);
        pending_.erase(id);
    }

    // Every object is checked whether referenced or not: the top-level BSDFs and textures that nothing referenced
    // are built now, in file order, and their errors are errors. Only a plugin that Mitsuba has and surfscatter
    // lacks is let pass in them, with a note (it cannot affect the image).
    void build_unreferenced() {
        for (const std::string& id : pending_order_) {
            const auto it = pending_.find(id);
            if (it == pending_.end()) continue;  // built when referenced
            const Node node = it->second;
            try {
                build_pending(node, id);
            } catch (const UnsupportedPlugin& e) {
                scene_->notes.push_back(fmt::format("{}: <{} id=\"{}\"> is referenced by nothing and not built: {}",
                                                    node.where(), node.tag(), printable(id), e.what()));
                building_.clear();
                pending_.erase(id);
            }
        }
    }

    // A <bsdf>, or a <ref> that names no texture (an undefined id is then reported where it is built).
    bool is_bsdf(const Node& node) { return node.tag() == "bsdf" || (node.tag() == "ref" && !names_texture(node)); }

    bool names_texture(const Node& ref) {
        const std::string id = attribute(ref, "id");
        const auto pending = pending_.find(id);
        if (pending != pending_.end()) return pending->second.tag() == "texture";
        const auto it = objects_.find(id);
        return it != objects_.end() && std::holds_alternative<TexturePtr>(it->second);
    }

    // Mitsuba 2 and 3 scenes (version="2.x.y" or "3.x.y"); 0.x scenes use Mitsuba 0.6's different names.
    void check_version(const Node& scene_node) {
        check_attributes(scene_node, {"version"});
        if (!scene_node.xml.attribute("version"))
            fail_at(scene_node, "<scene> needs a version attribute (version=\"3.0.0\")");
        const std::string version = attribute(scene_node, "version");
        int major = -1, minor = -1, patch = -1;
        char extra = 0;
        if (std::sscanf(version.c_str(), "%d.%d.%d%c", &major, &minor, &patch, &extra) != 3 || minor < 0 || patch < 0)
            fail_at(scene_node, "scene version '{}' is not major.minor.patch", printable(version));
        if (major != 2 && major != 3)
            fail_at(scene_node, "scene version {} is not supported: surfscatter reads Mitsuba 2.x and 3.x scenes{}", version,
                    major < 2 ? " (upgrade 0.x scenes with Mitsuba's converter: parameter names changed)" : "");
    }

    Object lookup(const Node& node, const char* kind) {
        check_leaf(node, {"id", "name"});
        const std::string id = attribute(node, "id");
        if (!objects_.count(id)) build_pending(node, id);
        const auto it = objects_.find(id);
        if (it == objects_.end()) fail_at(node, "reference to undefined id '{}'", printable(id));
        const bool is_bsdf = std::holds_alternative<MaterialPtr>(it->second);
        if (is_bsdf != (std::string(kind) == "bsdf")) fail_at(node, "id '{}' does not name a {}", printable(id), kind);
        return it->second;
    }

public:
    const Source& open(const fs::path& path, const Node* from) {
        auto source = std::make_unique<Source>();
        source->path = path;
        std::string text = from ? located(*from, "", [&] { return read_input_file(path, "scene file"); })
                                : read_input_file(path, "scene file");
        return parse(std::move(source), std::move(text));
    }

    const Source& parse(std::unique_ptr<Source> source, std::string text) {
        source->text = std::move(text);
        source->line_starts.push_back(0);
        for (std::size_t i = 0; i < source->text.size(); ++i)
            if (source->text[i] == '\n') source->line_starts.push_back(i + 1);
        const pugi::xml_parse_result result =
            source->document.load_buffer(source->text.data(), source->text.size(),
                                         pugi::parse_default | pugi::parse_comments | pugi::parse_fragment);
        if (!result)
            fail("{}:{}: XML syntax error: {}", source->shown_path(), source->line_of(result.offset), result.description());
        check_depth(*source);
        sources_.push_back(std::move(source));
        return *sources_.back();
    }

    // The loader builds nested plugins recursively: bound the nesting before building, walking the tree without
    // recursion so that a hostile file cannot exhaust the stack here either.
    static void check_depth(const Source& source) {
        pugi::xml_node node = source.document.first_child();
        int depth = 1;
        while (node) {
            if (depth > kMaxElementDepth)
                fail_at(Node{node, &source}, "elements nested more than {} deep", kMaxElementDepth);
            if (node.first_child()) {
                node = node.first_child();
                ++depth;
                continue;
            }
            while (node && !node.next_sibling()) {
                node = node.parent();
                --depth;
            }
            if (node) node = node.next_sibling();
        }
    }

private:
    std::map<std::string, std::string> defines_;
    std::unique_ptr<Scene> scene_;
    // Prepared maps by surface_file and preparation.
    std::map<std::pair<std::string, heightmap::Preparation>, std::shared_ptr<const heightmap::PreparedMap>> height_maps_;
    std::vector<std::unique_ptr<Source>> sources_;
    std::map<std::string, Object> objects_;
    std::set<std::string> names_;
    std::map<std::string, Node> pending_;  // top-level BSDFs and textures not referenced yet
    std::vector<std::string> pending_order_;  // their ids in file order
    std::map<std::string, Node> defaults_;  // <default> elements by name
    std::optional<Node> sensor_, integrator_;
    std::set<std::string> building_;
    std::map<std::string, std::string> command_line_defines_;
    std::set<std::string> used_defines_;
    ParameterSyntax syntax_;
    int include_depth_ = 0;
    int include_count_ = 0;
};

}  // namespace

bool is_parameter_name(std::string_view name) {
    return !name.empty() && std::all_of(name.begin(), name.end(), is_parameter_char);
}

std::unique_ptr<Scene> load_scene(const std::filesystem::path& path, const std::map<std::string, std::string>& defines,
                                  std::set<std::string>* used_parameters, ParameterSyntax syntax) {
    Loader loader(defines, syntax);
    const Source& root = loader.open(path, nullptr);
    return loader.load(root, used_parameters);
}

std::unique_ptr<Scene> load_scene_from_string(const std::string& xml, const std::filesystem::path& virtual_path,
                                              const std::map<std::string, std::string>& defines,
                                              std::set<std::string>* used_parameters) {
    Loader loader(defines);
    auto source = std::make_unique<Source>();
    source->path = virtual_path;
    const Source& root = loader.parse(std::move(source), xml);
    return loader.load(root, used_parameters);
}

}  // namespace surfscatter::render
