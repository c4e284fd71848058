#include "surfscatter/render/xml_loader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <variant>
#include <vector>

#include <pugixml.hpp>

#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/core/error.hpp"

namespace surfscatter::render {

namespace {

namespace fs = std::filesystem;

// One XML file (the scene or an include) with what is needed to turn byte offsets into line numbers.
struct Source {
    fs::path path;
    std::string text;
    std::vector<std::size_t> line_starts;
    pugi::xml_document document;

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

    std::string where() const { return fmt::format("{}:{}", source->path.string(), source->line_of(xml.offset_debug())); }
    std::string tag() const { return xml.name(); }
};

template <typename... Args>
[[noreturn]] void fail_at(const Node& node, fmt::format_string<Args...> format, Args&&... args) {
    throw Error(node.where() + ": " + fmt::format(format, std::forward<Args>(args)...));
}

using Object = std::variant<MaterialPtr, TexturePtr>;

class Loader {
public:
    explicit Loader(std::map<std::string, std::string> defines) : defines_(std::move(defines)) {}

    std::unique_ptr<Scene> load(const Source& root) {
        scene_ = std::make_unique<Scene>();
        const Node scene_node{root.document.child("scene"), &root};
        if (!scene_node.xml) throw Error(fmt::format("{}:1: the root element must be <scene>", root.path.string()));
        for (const auto& attr : scene_node.xml.attributes())
            if (std::string(attr.name()) != "version")
                fail_at(scene_node, "unknown attribute '{}' of <scene>", attr.name());
        load_children(scene_node);
        if (!has_sensor_) fail_at(scene_node, "the scene has no <sensor>");
        scene_->commit();
        return std::move(scene_);
    }

private:
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
            while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) ++j;
            const std::string name = text.substr(i + 1, j - i - 1);
            if (name.empty()) fail_at(node, "'$' without a parameter name in '{}'", text);
            const auto it = defines_.find(name);
            if (it == defines_.end())
                fail_at(node, "parameter ${} is not defined (pass -D {}=... or add <default name=\"{}\" .../>)", name, name, name);
            out += it->second;
            i = j;
        }
        return out;
    }

    void check_attributes(const Node& node, std::initializer_list<const char*> allowed) {
        for (const auto& attr : node.xml.attributes()) {
            const bool ok = std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return std::string(a) == attr.name(); });
            if (!ok) fail_at(node, "unknown attribute '{}' of <{}>", attr.name(), node.tag());
        }
    }

    double parse_double(const Node& node, const std::string& text, const std::string& what) {
        std::size_t used = 0;
        double v = 0;
        try {
            v = std::stod(text, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        while (used < text.size() && std::isspace(static_cast<unsigned char>(text[used]))) ++used;
        if (used == 0 || used != text.size() || !std::isfinite(v)) fail_at(node, "{}: '{}' is not a finite number", what, text);
        return v;
    }

    std::vector<double> parse_list(const Node& node, const std::string& text, const std::string& what) {
        std::vector<double> values;
        std::string item;
        std::string normalised = text;
        std::replace(normalised.begin(), normalised.end(), ',', ' ');
        std::istringstream in(normalised);
        while (in >> item) values.push_back(parse_double(node, item, what));
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
    class Properties {
    public:
        Properties(Loader& loader, const Node& owner) : loader_(loader), owner_(owner) {
            for (pugi::xml_node child : owner.xml.children()) {
                if (child.type() != pugi::node_element) continue;
                const Node node{child, owner.source};
                const std::string name = child.attribute("name") ? loader.substitute(node, child.attribute("name").value()) : "";
                if (name.empty()) {
                    unnamed_.push_back({node});
                    continue;
                }
                if (named_.count(name)) fail_at(node, "parameter '{}' given twice", name);
                named_.emplace(name, Property{node});
            }
        }

        const Node* find(const std::string& name) {
            auto it = named_.find(name);
            if (it == named_.end()) return nullptr;
            it->second.used = true;
            return &it->second.node;
        }

        const Node* find_typed(const std::string& name, const char* tag) {
            const Node* node = find(name);
            if (node && node->tag() != tag) fail_at(*node, "parameter '{}' must be a <{}>, got <{}>", name, tag, node->tag());
            return node;
        }

        double get_float(const std::string& name, double fallback) {
            const Node* node = find(name);
            if (!node) return fallback;
            if (node->tag() != "float" && node->tag() != "integer")
                fail_at(*node, "parameter '{}' must be a <float>, got <{}>", name, node->tag());
            loader_.check_attributes(*node, {"name", "value"});
            return loader_.parse_double(*node, loader_.attribute(*node, "value"), name);
        }
        double get_float_required(const std::string& name) {
            if (!named_.count(name)) fail_at(owner_, "<{}> needs the parameter '{}'", owner_.tag(), name);
            return get_float(name, 0);
        }
        int get_int(const std::string& name, int fallback) {
            const Node* node = find_typed(name, "integer");
            if (!node) return fallback;
            loader_.check_attributes(*node, {"name", "value"});
            const double v = loader_.parse_double(*node, loader_.attribute(*node, "value"), name);
            if (v != std::floor(v) || std::abs(v) > 2e9) fail_at(*node, "{}: '{}' is not an integer", name, v);
            return static_cast<int>(v);
        }
        bool get_bool(const std::string& name, bool fallback) {
            const Node* node = find_typed(name, "boolean");
            if (!node) return fallback;
            loader_.check_attributes(*node, {"name", "value"});
            const std::string v = loader_.attribute(*node, "value");
            if (v == "true") return true;
            if (v == "false") return false;
            fail_at(*node, "{}: boolean must be true or false, got '{}'", name, v);
        }
        std::string get_string(const std::string& name, const std::string& fallback) {
            const Node* node = find_typed(name, "string");
            if (!node) return fallback;
            loader_.check_attributes(*node, {"name", "value"});
            return loader_.attribute(*node, "value");
        }
        std::optional<Vec3> get_point(const std::string& name) {
            const Node* node = find(name);
            if (!node) return std::nullopt;
            if (node->tag() != "point" && node->tag() != "vector")
                fail_at(*node, "parameter '{}' must be a <point>, got <{}>", name, node->tag());
            loader_.check_attributes(*node, {"name", "value", "x", "y", "z"});
            return loader_.parse_xyz(*node, 0.0);
        }
        Transform get_transform(const std::string& name) {
            const Node* node = find_typed(name, "transform");
            return node ? loader_.build_transform(*node) : Transform();
        }
        // Unnamed nested objects of a kind (<bsdf>, <emitter>, <film>, ...), references included.
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
        std::vector<Node> take_unnamed_refs() {
            std::vector<Node> out;
            for (Property& p : unnamed_)
                if (!p.used && p.node.tag() == "ref") {
                    p.used = true;
                    out.push_back(p.node);
                }
            return out;
        }
        void check_all_used(const std::string& plugin) {
            for (auto& [name, p] : named_)
                if (!p.used) fail_at(p.node, "unknown parameter '{}' of {} (<{}>)", name, plugin, p.node.tag());
            for (const Property& p : unnamed_)
                if (!p.used) fail_at(p.node, "unexpected <{}> inside {}", p.node.tag(), plugin);
        }
        bool has(const std::string& name) const { return named_.count(name) != 0; }

    private:
        Loader& loader_;
        Node owner_;
        std::map<std::string, Property> named_;
        std::vector<Property> unnamed_;
    };

    // ---------------------------------------------------------------- transforms

    Transform build_transform(const Node& node) {
        check_attributes(node, {"name"});
        Transform t;
        for (pugi::xml_node child : node.xml.children()) {
            if (child.type() != pugi::node_element) continue;
            const Node c{child, node.source};
            const std::string tag = c.tag();
            Transform op;
            try {
                if (tag == "translate") {
                    check_attributes(c, {"value", "x", "y", "z"});
                    op = Transform::translate(parse_xyz(c, 0.0));
                } else if (tag == "scale") {
                    check_attributes(c, {"value", "x", "y", "z"});
                    op = Transform::scale(parse_xyz(c, 1.0));
                } else if (tag == "rotate") {
                    check_attributes(c, {"value", "x", "y", "z", "angle"});
                    const Vec3 axis = parse_xyz(c, 0.0);
                    op = Transform::rotate(axis, parse_double(c, attribute(c, "angle"), "angle"));
                } else if (tag == "matrix") {
                    check_attributes(c, {"value"});
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
                    check_attributes(c, {"origin", "target", "up"});
                    auto vec = [&](const char* a) {
                        const auto v = parse_list(c, attribute(c, a), a);
                        if (v.size() != 3) fail_at(c, "lookat {} needs 3 numbers", a);
                        return Vec3(v[0], v[1], v[2]);
                    };
                    const Vec3 up = c.xml.attribute("up") ? vec("up") : Vec3(0, 1, 0);
                    op = Transform::look_at(vec("origin"), vec("target"), up);
                } else {
                    fail_at(c, "unknown transform operation <{}>", tag);
                }
            } catch (const Error& e) {
                const std::string message = e.what();
                if (message.rfind(c.source->path.string(), 0) == 0) throw;
                fail_at(c, "{}", message);
            }
            t = op * t;  // later operations apply after earlier ones (Mitsuba)
        }
        return t;
    }

    // ---------------------------------------------------------------- spectra and textures

    // float, <spectrum>, <rgb> -> a spectrum; `illuminant` selects the emission variant of RGB upsampling.
    SpectrumPtr build_spectrum(const Node& node, bool illuminant) {
        const std::string tag = node.tag();
        if (tag == "float") {
            check_attributes(node, {"name", "value"});
            return make_constant_spectrum(parse_double(node, attribute(node, "value"), "value"));
        }
        if (tag == "rgb") {
            check_attributes(node, {"name", "value"});
            const auto v = parse_list(node, attribute(node, "value"), "rgb");
            if (v.size() != 1 && v.size() != 3) fail_at(node, "<rgb> needs 1 or 3 numbers, got {}", v.size());
            const std::array<double, 3> rgb = v.size() == 1 ? std::array<double, 3>{v[0], v[0], v[0]}
                                                            : std::array<double, 3>{v[0], v[1], v[2]};
            for (double x : rgb)
                if (x < 0) fail_at(node, "<rgb> values must be non-negative, got {}", x);
            try {
                return illuminant ? make_rgb_illuminant(rgb) : make_rgb_reflectance(rgb);
            } catch (const Error& e) {
                fail_at(node, "{}", e.what());
            }
        }
        if (tag == "spectrum") {
            const std::string type = node.xml.attribute("type") ? attribute(node, "type") : "";
            if (type == "blackbody") {
                check_attributes(node, {"name", "type"});
                Properties props(*this, node);
                const double temperature = props.get_float_required("temperature");
                const double scale = props.get_float("scale", 1.0);
                props.check_all_used("spectrum 'blackbody'");
                if (!(temperature > 0)) fail_at(node, "blackbody temperature must be positive, got {}", temperature);
                return make_blackbody_spectrum(temperature, scale);
            }
            if (!type.empty()) fail_at(node, "unknown spectrum type '{}' (value list or blackbody)", type);
            check_attributes(node, {"name", "value"});
            const std::string value = attribute(node, "value");
            if (value.find(':') == std::string::npos) return make_constant_spectrum(parse_double(node, value, "spectrum value"));
            std::vector<double> lambdas, values;
            std::string normalised = value;
            std::replace(normalised.begin(), normalised.end(), ',', ' ');
            std::istringstream in(normalised);
            std::string pair;
            while (in >> pair) {
                const auto colon = pair.find(':');
                if (colon == std::string::npos) fail_at(node, "spectrum entry '{}' is not lambda:value", pair);
                lambdas.push_back(parse_double(node, pair.substr(0, colon), "wavelength"));
                values.push_back(parse_double(node, pair.substr(colon + 1), "spectrum value"));
            }
            try {
                return make_tabulated_spectrum(lambdas, values);
            } catch (const Error& e) {
                fail_at(node, "{}", e.what());
            }
        }
        fail_at(node, "expected <float>, <spectrum> or <rgb>, got <{}>", tag);
    }

    TexturePtr build_texture_param(const Node& node) {
        const std::string tag = node.tag();
        if (tag == "texture") return build_texture(node);
        if (tag == "ref") return std::get<TexturePtr>(lookup(node, "texture"));
        return make_constant_texture(build_spectrum(node, false));
    }

    TexturePtr texture_or(Properties& props, const std::string& name, double fallback) {
        const Node* node = props.find(name);
        return node ? build_texture_param(*node) : make_constant_texture(make_constant_spectrum(fallback));
    }

    TexturePtr build_texture(const Node& node) {
        check_attributes(node, {"type", "name", "id"});
        const std::string type = attribute(node, "type");
        Properties props(*this, node);
        TexturePtr texture;
        if (type == "checkerboard") {
            TexturePtr c0 = texture_or(props, "color0", 0.4), c1 = texture_or(props, "color1", 0.2);
            const Transform to_uv = props.get_transform("to_uv");
            texture = make_checkerboard_texture(c0, c1, to_uv);
        } else if (type == "bitmap") {
            BitmapOptions options;
            const std::string filename = props.get_string("filename", "");
            if (filename.empty()) fail_at(node, "bitmap needs the parameter 'filename'");
            options.filename = resolve(node, filename);
            options.raw = props.get_bool("raw", false);
            const std::string filter = props.get_string("filter_type", "bilinear");
            if (filter != "bilinear" && filter != "nearest") fail_at(node, "filter_type must be bilinear or nearest, got '{}'", filter);
            options.bilinear = filter == "bilinear";
            const std::string wrap = props.get_string("wrap_mode", "repeat");
            if (wrap != "repeat" && wrap != "clamp") fail_at(node, "wrap_mode must be repeat or clamp, got '{}'", wrap);
            options.repeat = wrap == "repeat";
            options.to_uv = props.get_transform("to_uv");
            try {
                texture = make_bitmap_texture(options);
            } catch (const Error& e) {
                fail_at(node, "{}", e.what());
            }
        } else {
            fail_at(node, "unknown texture plugin '{}' (bitmap, checkerboard)", type);
        }
        props.check_all_used("texture '" + type + "'");
        register_id(node, texture);
        return texture;
    }

    // ---------------------------------------------------------------- BSDFs

    void read_surface_options(Properties& props, bsdf::ModelOptions& o, const Node& node, bool with_fresnel) {
        o.material = props.get_string("material", o.material);
        const std::string psd = props.get_string("psd", "");
        if (!psd.empty()) o.surface.psd = bsdf::parse_psd(psd);
        o.surface.sigma = props.get_float("sigma", o.surface.sigma);
        o.surface.corr_length = props.get_float("corr_length", o.surface.corr_length);
        o.surface.gamma = props.get_float("gamma", o.surface.gamma);
        const std::string file = props.get_string("surface_file", "");
        if (!file.empty()) {
            o.surface.surface_file = resolve(node, file).string();
            if (psd.empty()) o.surface.psd = bsdf::PsdKind::file;
        }
        const std::string form = props.get_string("form", "");
        if (!form.empty()) o.surface.form = surface::parse_form(form, "form");
        if (with_fresnel) {
            const std::string fresnel = props.get_string("fresnel", "");
            if (!fresnel.empty()) o.fresnel = bsdf::parse_fresnel(fresnel);
        }
    }

    void read_ghs_options(Properties& props, bsdf::ModelOptions& o) {
        const std::string method = props.get_string("method", "");
        if (!method.empty()) o.method = bsdf::parse_method(method);
        const std::string truncation = props.get_string("truncation", "");
        if (!truncation.empty()) o.truncation = bsdf::parse_truncation(truncation);
        o.epsilon = props.get_float("epsilon", o.epsilon);
        o.renormalization = props.get_bool("renormalization", o.renormalization);
    }

    MaterialPtr build_model(const Node& node, Properties& props, const std::string& type) {
        bsdf::ModelOptions o;
        try {
            if (type == "roughconductor") {
                o.model = bsdf::ModelKind::ggx;
                o.alpha = props.get_float("alpha", 0.1);
                const std::string distribution = props.get_string("distribution", "ggx");
                if (distribution != "ggx") fail_at(node, "roughconductor supports distribution 'ggx' only, got '{}'", distribution);
                o.material = props.get_string("material", "perfect");
                if (o.material == "none") o.material = "perfect";
            } else if (type == "ggx_stats") {
                o.model = bsdf::ModelKind::ggx;
                o.alpha_from = bsdf::AlphaFrom::measured;
                const std::string from = props.get_string("alpha_from", "");
                if (!from.empty()) o.alpha_from = bsdf::parse_alpha_from(from);
                o.smoothing = props.get_float("smoothing", o.smoothing);
                o.alpha = props.get_float("alpha", o.alpha);
                read_surface_options(props, o, node, true);
            } else if (type == "ghs") {
                o.model = bsdf::ModelKind::ghs;
                read_ghs_options(props, o);
                read_surface_options(props, o, node, true);
            } else if (type == "ghs_ssa") {
                o.model = bsdf::ModelKind::ghs_ssa;
                const std::string form = props.get_string("ssa_form", "");
                if (!form.empty()) o.ssa_form = bsdf::parse_ssa_form(form);
                o.renormalization = props.get_bool("renormalization", o.renormalization);
                read_surface_options(props, o, node, true);
            } else {  // two_scale
                o.model = bsdf::ModelKind::two_scale;
                o.cutoff_wavelengths = props.get_float("cutoff_wavelengths", o.cutoff_wavelengths);
                const std::string ndf = props.get_string("macro_ndf", "");
                if (!ndf.empty()) o.macro_ndf = bsdf::parse_macro_ndf(ndf);
                read_ghs_options(props, o);
                read_surface_options(props, o, node, true);
            }
            props.check_all_used("bsdf '" + type + "'");
            bsdf::validate(o);
            share_height_map(o.surface);
            return make_model_material(std::shared_ptr<const bsdf::Bsdf>(bsdf::make_bsdf(o)));
        } catch (const Error& e) {
            const std::string message = e.what();
            if (message.rfind(node.source->path.string() + ":", 0) == 0) throw;
            fail_at(node, "bsdf '{}': {}", type, message);
        }
    }

    // Each surface_file is read once per scene (several BSDFs may use it) and reported in the scene's notes.
    void share_height_map(bsdf::SurfaceOptions& surface) {
        if (surface.psd != bsdf::PsdKind::file) return;
        auto& map = height_maps_[surface.surface_file];
        if (!map) {
            bsdf::load_height_map(surface);
            map = surface.height_map;
            scene_->notes.push_back(surface::describe(*map));
        }
        surface.height_map = map;
    }

    MaterialPtr build_bsdf(const Node& node) {
        if (node.tag() == "ref") return std::get<MaterialPtr>(lookup(node, "bsdf"));
        check_attributes(node, {"type", "id", "name"});
        const std::string type = attribute(node, "type");
        Properties props(*this, node);
        MaterialPtr material;
        if (type == "diffuse") {
            material = make_diffuse(texture_or(props, "reflectance", 0.5));
        } else if (type == "conductor") {
            std::optional<material::Conductor> conductor;
            SpectrumPtr eta, k;
            const Node* eta_node = props.find("eta");
            const Node* k_node = props.find("k");
            const std::string name = props.get_string("material", "");
            if (eta_node || k_node) {
                if (!eta_node || !k_node) fail_at(node, "conductor needs both eta and k");
                if (!name.empty()) fail_at(node, "conductor takes either material or eta/k, not both");
                eta = build_spectrum(*eta_node, false);
                k = build_spectrum(*k_node, false);
            } else {
                try {
                    conductor = material::Conductor::from_name(name.empty() || name == "none" ? "perfect" : name);
                } catch (const Error& e) {
                    fail_at(node, "conductor material: {}", e.what());
                }
            }
            TexturePtr specular = texture_or(props, "specular_reflectance", 1.0);
            try {
                material = make_smooth_conductor(conductor, eta, k, specular);
            } catch (const Error& e) {
                fail_at(node, "conductor: {}", e.what());
            }
        } else if (type == "twosided") {
            std::vector<Node> nested = props.take_unnamed("bsdf");
            for (const Node& r : props.take_unnamed_refs()) nested.push_back(r);
            if (nested.size() != 1) fail_at(node, "twosided needs exactly one nested <bsdf>, got {}", nested.size());
            material = make_twosided(build_bsdf(nested[0]));
        } else if (type == "roughconductor" || type == "ghs" || type == "ghs_ssa" || type == "ggx_stats" ||
                   type == "two_scale") {
            material = build_model(node, props, type);
        } else {
            fail_at(node, "unknown bsdf plugin '{}' (diffuse, conductor, roughconductor, twosided, ghs, ghs_ssa, "
                          "ggx_stats, two_scale)", type);
        }
        props.check_all_used("bsdf '" + type + "'");
        register_id(node, material);
        return material;
    }

    // ---------------------------------------------------------------- shapes, emitters, sensor

    SpectrumPtr spectrum_param(Properties& props, const std::string& name, const Node& owner, bool illuminant) {
        const Node* node = props.find(name);
        if (!node) fail_at(owner, "<{}> needs the parameter '{}'", owner.tag(), name);
        return build_spectrum(*node, illuminant);
    }

    void build_shape(const Node& node) {
        check_attributes(node, {"type", "id"});
        const std::string type = attribute(node, "type");
        Properties props(*this, node);
        const Transform to_world = props.get_transform("to_world");
        const bool flip = props.get_bool("flip_normals", false);
        MaterialPtr material;
        std::vector<Node> bsdfs = props.take_unnamed("bsdf");
        for (const Node& r : props.take_unnamed_refs()) bsdfs.push_back(r);
        if (bsdfs.size() > 1) fail_at(node, "a shape takes one <bsdf>, got {}", bsdfs.size());
        if (!bsdfs.empty()) material = build_bsdf(bsdfs[0]);
        SpectrumPtr radiance;
        const std::vector<Node> emitters = props.take_unnamed("emitter");
        if (emitters.size() > 1) fail_at(node, "a shape takes one <emitter>, got {}", emitters.size());
        if (!emitters.empty()) {
            const Node& e = emitters[0];
            check_attributes(e, {"type"});
            if (attribute(e, "type") != "area") fail_at(e, "a shape's emitter must be of type 'area', got '{}'", attribute(e, "type"));
            Properties eprops(*this, e);
            radiance = spectrum_param(eprops, "radiance", e, true);
            eprops.check_all_used("emitter 'area'");
        }
        if (!material && !radiance) material = make_diffuse(make_constant_texture(make_constant_spectrum(0.5)));  // Mitsuba's default

        try {
            if (type == "sphere") {
                const Vec3 center = props.get_point("center").value_or(Vec3(0, 0, 0));
                const double radius = props.get_float("radius", 1.0);
                const Vec3 ex = to_world.vector({1, 0, 0}), ey = to_world.vector({0, 1, 0}), ez = to_world.vector({0, 0, 1});
                const double s = ex.length();
                if (std::abs(ey.length() - s) > 1e-9 * s || std::abs(ez.length() - s) > 1e-9 * s)
                    fail_at(node, "sphere to_world must scale uniformly");
                props.check_all_used("shape 'sphere'");
                scene_->add_sphere(to_world.point(center), radius * s, flip, material, radiance);
                return;
            }
            TriangleMesh mesh;
            if (type == "rectangle") mesh = make_rectangle();
            else if (type == "disk") mesh = make_disk();
            else if (type == "cube") mesh = make_cube();
            else if (type == "obj" || type == "ply") {
                const std::string filename = props.get_string("filename", "");
                if (filename.empty()) fail_at(node, "shape '{}' needs the parameter 'filename'", type);
                const fs::path path = resolve(node, filename);
                mesh = type == "obj" ? load_obj(path) : load_ply(path);
                if (props.get_bool("face_normals", false)) mesh.normals.clear();
            } else {
                fail_at(node, "unknown shape plugin '{}' (rectangle, disk, cube, sphere, obj, ply)", type);
            }
            props.check_all_used("shape '" + type + "'");
            transform_mesh(mesh, to_world, flip);
            scene_->add_mesh(std::move(mesh), material, radiance);
        } catch (const Error& e) {
            const std::string message = e.what();
            if (message.rfind(node.source->path.string() + ":", 0) == 0) throw;
            fail_at(node, "shape '{}': {}", type, message);
        }
    }

    void build_emitter(const Node& node) {
        check_attributes(node, {"type", "id"});
        const std::string type = attribute(node, "type");
        Properties props(*this, node);
        if (type == "point") {
            const Transform to_world = props.get_transform("to_world");
            Vec3 position = to_world.point({0, 0, 0});
            if (auto p = props.get_point("position")) position = *p;
            scene_->add_point_light(position, spectrum_param(props, "intensity", node, true));
        } else if (type == "constant") {
            try {
                scene_->set_environment(spectrum_param(props, "radiance", node, true));
            } catch (const Error& e) {
                const std::string message = e.what();
                if (message.rfind(node.source->path.string() + ":", 0) == 0) throw;
                fail_at(node, "{}", message);
            }
        } else if (type == "area") {
            fail_at(node, "an area emitter must be nested in a <shape>");
        } else {
            fail_at(node, "unknown emitter plugin '{}' (point, area, constant)", type);
        }
        props.check_all_used("emitter '" + type + "'");
    }

    void build_sensor(const Node& node) {
        check_attributes(node, {"type", "id"});
        const std::string type = attribute(node, "type");
        if (type != "perspective") fail_at(node, "unknown sensor plugin '{}' (perspective)", type);
        if (has_sensor_) fail_at(node, "only one <sensor> is supported");
        has_sensor_ = true;
        Properties props(*this, node);
        CameraSettings& c = scene_->camera;
        c.to_world = props.get_transform("to_world");
        c.fov_degrees = props.get_float("fov", c.fov_degrees);
        c.fov_axis = props.get_string("fov_axis", c.fov_axis);
        c.near_clip = props.get_float("near_clip", c.near_clip);
        c.far_clip = props.get_float("far_clip", c.far_clip);
        c.principal_point_offset_x = props.get_float("principal_point_offset_x", 0.0);
        c.principal_point_offset_y = props.get_float("principal_point_offset_y", 0.0);
        for (const Node& film : props.take_unnamed("film")) build_film(film);
        for (const Node& sampler : props.take_unnamed("sampler")) build_sampler(sampler);
        props.check_all_used("sensor 'perspective'");
        try {
            Camera check(c, scene_->film.width, scene_->film.height);
        } catch (const Error& e) {
            fail_at(node, "{}", e.what());
        }
    }

    void build_film(const Node& node) {
        check_attributes(node, {"type", "id"});
        const std::string type = attribute(node, "type");
        if (type != "hdrfilm") fail_at(node, "unknown film plugin '{}' (hdrfilm)", type);
        Properties props(*this, node);
        FilmSettings& f = scene_->film;
        f.width = props.get_int("width", f.width);
        f.height = props.get_int("height", f.height);
        if (f.width <= 0 || f.height <= 0) fail_at(node, "film size must be positive, got {}x{}", f.width, f.height);
        f.crop_offset_x = props.get_int("crop_offset_x", 0);
        f.crop_offset_y = props.get_int("crop_offset_y", 0);
        f.crop_width = props.get_int("crop_width", 0);
        f.crop_height = props.get_int("crop_height", 0);
        try {
            f.check_crop();
        } catch (const Error& e) {
            fail_at(node, "{}", e.what());
        }
        f.exposure = props.get_float("exposure", f.exposure);
        f.white_balance = props.get_string("white_balance", f.white_balance);
        const std::string format = props.get_string("pixel_format", "rgb");
        if (format != "rgb") fail_at(node, "pixel_format must be rgb, got '{}'", format);
        for (const Node& r : props.take_unnamed("rfilter")) {
            check_attributes(r, {"type", "name"});
            const std::string filter = attribute(r, "type");
            if (filter != "box" && filter != "gaussian") fail_at(r, "unknown rfilter plugin '{}' (box, gaussian)", filter);
            Properties rprops(*this, r);
            rprops.check_all_used("rfilter '" + filter + "'");
            f.filter = filter;
        }
        props.check_all_used("film 'hdrfilm'");
    }

    void build_sampler(const Node& node) {
        check_attributes(node, {"type", "id"});
        const std::string type = attribute(node, "type");
        if (type != "independent") fail_at(node, "unknown sampler plugin '{}' (independent)", type);
        Properties props(*this, node);
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
        if (type != "path") fail_at(node, "unknown integrator plugin '{}' (path)", type);
        Properties props(*this, node);
        IntegratorSettings& s = scene_->integrator;
        s.max_depth = props.get_int("max_depth", s.max_depth);
        s.rr_depth = props.get_int("rr_depth", s.rr_depth);
        s.strategy = props.get_string("strategy", s.strategy);
        if (s.max_depth < -1 || s.max_depth == 0) fail_at(node, "max_depth must be -1 or positive, got {}", s.max_depth);
        if (s.rr_depth < 1) fail_at(node, "rr_depth must be positive, got {}", s.rr_depth);
        if (s.strategy != "mis" && s.strategy != "bsdf" && s.strategy != "emitter")
            fail_at(node, "strategy must be mis, bsdf or emitter, got '{}'", s.strategy);
        props.check_all_used("integrator 'path'");
    }

    // ---------------------------------------------------------------- scene level

    void load_children(const Node& scene_node) {
        for (pugi::xml_node child : scene_node.xml.children()) {
            if (child.type() != pugi::node_element) continue;
            const Node node{child, scene_node.source};
            const std::string tag = node.tag();
            if (tag == "default") {
                check_attributes(node, {"name", "value"});
                const std::string name = node.xml.attribute("name").value();
                if (name.empty()) fail_at(node, "<default> needs a name");
                if (!node.xml.attribute("value")) fail_at(node, "<default> needs a value");
                defines_.emplace(name, node.xml.attribute("value").value());  // -D values win
            } else if (tag == "include") {
                check_attributes(node, {"filename"});
                const fs::path path = resolve(node, attribute(node, "filename"));
                if (++include_depth_ > 16) fail_at(node, "includes nested too deeply (a cycle?)");
                const Source& included = open(path, &node);
                const Node root{included.document.child("scene"), &included};
                if (!root.xml) fail_at(node, "included file {} has no <scene> root", path.string());
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
            } else if (tag == "bsdf") {
                if (!node.xml.attribute("id")) fail_at(node, "a top-level <bsdf> needs an id");
                build_bsdf(node);
            } else if (tag == "texture") {
                if (!node.xml.attribute("id")) fail_at(node, "a top-level <texture> needs an id");
                build_texture(node);
            } else {
                fail_at(node, "unknown element <{}> in <scene>", tag);
            }
        }
    }

    fs::path resolve(const Node& node, const std::string& filename) {
        fs::path p(filename);
        if (p.is_relative()) p = node.source->path.parent_path() / p;
        if (!fs::exists(p)) fail_at(node, "file not found: {}", p.string());
        return p;
    }

    void register_id(const Node& node, Object object) {
        if (!node.xml.attribute("id")) return;
        const std::string id = attribute(node, "id");
        if (!objects_.emplace(id, std::move(object)).second) fail_at(node, "duplicate id '{}'", id);
    }

    Object lookup(const Node& node, const char* kind) {
        check_attributes(node, {"id", "name"});
        const std::string id = attribute(node, "id");
        const auto it = objects_.find(id);
        if (it == objects_.end()) fail_at(node, "reference to undefined id '{}'", id);
        const bool is_bsdf = std::holds_alternative<MaterialPtr>(it->second);
        if (is_bsdf != (std::string(kind) == "bsdf")) fail_at(node, "id '{}' does not name a {}", id, kind);
        return it->second;
    }

public:
    const Source& open(const fs::path& path, const Node* from) {
        auto source = std::make_unique<Source>();
        source->path = path;
        std::ifstream in(path, std::ios::binary);
        if (!in) {
            if (from) fail_at(*from, "cannot open scene file {}", path.string());
            fail("cannot open scene file {}", path.string());
        }
        std::ostringstream buffer;
        buffer << in.rdbuf();
        return parse(std::move(source), buffer.str());
    }

    const Source& parse(std::unique_ptr<Source> source, std::string text) {
        source->text = std::move(text);
        source->line_starts.push_back(0);
        for (std::size_t i = 0; i < source->text.size(); ++i)
            if (source->text[i] == '\n') source->line_starts.push_back(i + 1);
        const pugi::xml_parse_result result =
            source->document.load_buffer(source->text.data(), source->text.size(), pugi::parse_default | pugi::parse_comments);
        if (!result)
            fail("{}:{}: XML syntax error: {}", source->path.string(), source->line_of(result.offset), result.description());
        sources_.push_back(std::move(source));
        return *sources_.back();
    }

private:
    std::map<std::string, std::string> defines_;
    std::unique_ptr<Scene> scene_;
    std::map<std::string, std::shared_ptr<const surface::HeightMap>> height_maps_;  // by surface_file
    std::vector<std::unique_ptr<Source>> sources_;
    std::map<std::string, Object> objects_;
    bool has_sensor_ = false;
    int include_depth_ = 0;
};

}  // namespace

std::unique_ptr<Scene> load_scene(const std::filesystem::path& path, const std::map<std::string, std::string>& defines) {
    if (!std::filesystem::exists(path)) fail("scene file not found: {}", path.string());
    Loader loader(defines);
    const Source& root = loader.open(path, nullptr);
    return loader.load(root);
}

std::unique_ptr<Scene> load_scene_from_string(const std::string& xml, const std::filesystem::path& virtual_path,
                                              const std::map<std::string, std::string>& defines) {
    Loader loader(defines);
    auto source = std::make_unique<Source>();
    source->path = virtual_path;
    const Source& root = loader.parse(std::move(source), xml);
    return loader.load(root);
}

}  // namespace surfscatter::render
