#include "surfscatter/study/study.hpp"

#include <cmath>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/render/scene.hpp"
#include "surfscatter/study/json_input.hpp"

namespace surfscatter::study {

namespace {

using nlohmann::json;

// A JSON value with the path that leads to it, for messages: "study.json: render.spp: ...".
struct Node {
    const json& value;
    std::string path;
    const std::string& origin;

    Node operator[](const std::string& key) const {
        return {value.at(key), (path.empty() ? "" : path + ".") + printable(key), origin};
    }
    Node operator[](std::size_t i) const { return {value.at(i), fmt::format("{}[{}]", path, i), origin}; }

    template <typename... Args>
    [[noreturn]] void error(fmt::format_string<Args...> format, Args&&... args) const {
        const std::string message = fmt::format(format, std::forward<Args>(args)...);
        throw Error(path.empty() ? fmt::format("{}: {}", origin, message) : fmt::format("{}: {}: {}", origin, path, message));
    }

    void require(json::value_t type, const char* name) const {
        if (value.type() != type) error("must be {}, got {}", name, quoted_json(value));
    }

    // The object's keys must be among `known`.
    void only(std::initializer_list<const char*> known) const {
        require(json::value_t::object, "an object");
        for (const auto& [key, v] : value.items()) {
            bool ok = false;
            for (const char* k : known) ok = ok || key == k;
            if (!ok) {
                std::string list;
                for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
                error("unknown key '{}' (known: {})", printable(key), list);
            }
        }
    }

    bool has(const std::string& key) const { return value.contains(key); }

    double number() const {
        if (!value.is_number()) error("must be a number, got {}", quoted_json(value));
        const double v = value.get<double>();
        if (!std::isfinite(v)) error("must be finite");
        return v;
    }

    int positive_int() const {
        if (!value.is_number_integer() || value.get<long long>() <= 0 || value.get<long long>() > (1LL << 30))
            error("must be a positive integer, got {}", quoted_json(value));
        return static_cast<int>(value.get<long long>());
    }

    std::string string() const {
        if (!value.is_string()) error("must be a string, got {}", quoted_json(value));
        return value.get<std::string>();
    }

    // A parameter value: string, number (shortest form that reads back exactly) or boolean.
    std::string scalar() const {
        if (value.is_string()) return value.get<std::string>();
        if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
        if (value.is_number_integer()) return std::to_string(value.get<long long>());
        if (value.is_number()) return fmt::format("{}", number());
        error("must be a string, number or boolean, got {}", quoted_json(value));
    }

    std::vector<double> numbers() const {
        require(json::value_t::array, "a list of numbers");
        std::vector<double> out;
        for (std::size_t i = 0; i < value.size(); ++i) out.push_back((*this)[i].number());
        if (out.empty()) error("must not be empty");
        return out;
    }
};

void check_name(const Node& node, const std::string& name) {
    if (name.empty()) node.error("needs a non-empty name");
    for (const char c : name)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
            node.error("name '{}' may only hold letters, digits, '_', '-' and '.' (it names files)", printable(name));
    if (name == "." || name == "..") node.error("name '{}' would name a folder", name);
}

Parameters parameters_of(const Node& node) {
    node.require(json::value_t::object, "an object of name: value");
    Parameters out;
    for (const auto& [key, v] : node.value.items()) out[key] = node[key].scalar();
    return out;
}

// `models`, `surfaces`, `lamps`: objects with "name", optional "label", and parameters.
std::vector<Variant> variants(const Node& node) {
    std::vector<Variant> out;
    if (!node.value.is_array()) node.error("must be a list of objects");
    if (node.value.empty()) node.error("must not be empty");
    std::set<std::string> names;
    for (std::size_t i = 0; i < node.value.size(); ++i) {
        const Node entry = node[i];
        entry.require(json::value_t::object, "an object");
        Variant v;
        v.origin = fmt::format("{}: {}", entry.origin, entry.path);
        if (!entry.has("name")) entry.error("needs a \"name\"");
        v.name = entry["name"].string();
        check_name(entry["name"], v.name);
        if (!names.insert(v.name).second) entry["name"].error("'{}' is used twice", v.name);
        v.label = entry.has("label") ? entry["label"].string() : v.name;
        for (const auto& [key, value] : entry.value.items())
            if (key != "name" && key != "label") v.parameters[key] = entry[key].scalar();
        out.push_back(std::move(v));
    }
    return out;
}

AngleSettings angles(const Node& node) {
    node.only({"theta_i", "phi_i"});
    AngleSettings a;
    if (!node.has("theta_i")) node.error("needs \"theta_i\" (incidence angles in degrees)");
    a.theta_i = node["theta_i"].numbers();
    for (std::size_t i = 0; i < a.theta_i.size(); ++i)
        if (a.theta_i[i] < 0 || a.theta_i[i] >= 90) node["theta_i"][i].error("must be in [0, 90) degrees, got {}", a.theta_i[i]);
    if (node.has("phi_i")) a.phi_i = node["phi_i"].number();
    return a;
}

RenderSettings render_settings(const Node& node) {
    node.only({"spp", "width", "height", "seed", "parameters", "crop", "overview", "columns"});
    RenderSettings r;
    if (node.has("spp")) r.spp = node["spp"].positive_int();
    if (node.has("width")) r.width = node["width"].positive_int();
    if (node.has("height")) r.height = node["height"].positive_int();
    if (node.has("seed")) {
        const Node seed = node["seed"];
        if (!seed.value.is_number_unsigned()) seed.error("must be a non-negative integer, got {}", quoted_json(seed.value));
        r.seed = seed.value.get<std::uint64_t>();
    }
    if (node.has("parameters")) r.parameters = parameters_of(node["parameters"]);
    if (node.has("crop")) {
        const Node crop = node["crop"];
        crop.only({"focus", "radius"});
        if (!crop.has("focus") || !crop.has("radius")) crop.error("needs \"focus\" [x, y, z] and \"radius\"");
        const std::vector<double> focus = crop["focus"].numbers();
        if (focus.size() != 3) crop["focus"].error("needs 3 numbers x, y, z, got {}", focus.size());
        Crop c;
        for (std::size_t i = 0; i < 3; ++i) {
            if (!(std::abs(focus[i]) <= render::kMaxSceneCoordinate))
                crop["focus"][i].error("must be within +-{:g} (scene units), got {}", render::kMaxSceneCoordinate, focus[i]);
            c.focus[i] = focus[i];
        }
        c.radius = crop["radius"].number();
        if (!(c.radius > 0 && c.radius <= render::kMaxSceneCoordinate))
            crop["radius"].error("must be > 0 and at most {:g}, got {}", render::kMaxSceneCoordinate, c.radius);
        r.crop = c;
        r.overview = true;
    }
    if (node.has("overview")) {
        const Node overview = node["overview"];
        overview.require(json::value_t::boolean, "true or false");
        r.overview = overview.value.get<bool>();
        if (r.overview && !r.crop) overview.error("an overview outlines the crop: give render.crop too");
    }
    if (node.has("columns")) r.columns = node["columns"].positive_int();
    return r;
}

}  // namespace

std::filesystem::path Study::resolve(const std::string& path) const {
    const std::filesystem::path p(path);
    return std::filesystem::absolute(p.is_absolute() ? p : base / p).lexically_normal();
}

Parameters Study::with_absolute_files(Parameters values) const {
    if (const auto it = values.find("surface_file"); it != values.end()) it->second = resolve(it->second).string();
    return values;
}

Study parse_study(const std::string& text, const std::filesystem::path& base, const std::string& origin) {
    const json document = parse_json_input(text, origin);
    const Node root{document, "", origin};
    if (!document.is_object()) throw Error(fmt::format("{}: the study must be a JSON object", origin));
    root.only({"scene", "views", "parameters", "models", "surfaces", "lamps", "wavelengths", "render", "brdf_slices",
               "albedo"});
    Study s;
    s.origin = origin;
    s.base = base;
    s.folder = base;
    if (!root.has("models")) throw Error(fmt::format("{}: the study needs \"models\"", origin));
    s.models = variants(root["models"]);
    s.surfaces = root.has("surfaces") ? variants(root["surfaces"]) : std::vector<Variant>{Variant{}};
    s.lamps = root.has("lamps") ? variants(root["lamps"]) : std::vector<Variant>{Variant{}};
    if (root.has("parameters")) s.parameters = parameters_of(root["parameters"]);
    if (root.has("render")) s.render = render_settings(root["render"]);
    if (root.has("brdf_slices")) s.slices = angles(root["brdf_slices"]);
    if (root.has("albedo")) s.albedo = angles(root["albedo"]);
    if (!s.render && !s.slices && !s.albedo)
        throw Error(fmt::format("{}: nothing to do: give \"render\", \"brdf_slices\" and/or \"albedo\"", origin));
    if (s.render) {
        if (!root.has("scene")) throw Error(fmt::format("{}: \"render\" needs \"scene\"", origin));
        s.scene = root["scene"].string();
        if (!root.has("views")) throw Error(fmt::format("{}: \"render\" needs \"views\" (values of the scene's $view)", origin));
        const Node views = root["views"];
        if (!views.value.is_array() || views.value.empty()) views.error("must be a non-empty list");
        std::set<std::string> seen;
        for (std::size_t i = 0; i < views.value.size(); ++i) {
            const std::string v = views[i].scalar();
            check_name(views[i], v);
            if (!seen.insert(v).second) views[i].error("view '{}' is listed twice", v);
            s.views.push_back(v);
        }
    } else {
        for (const char* key : {"scene", "views"})
            if (root.has(key)) root[key].error("is only used by renders: add \"render\" or remove it");
        if (root.has("lamps")) root["lamps"].error("lamps only apply to renders: add \"render\" or remove them");
    }
    // A height map that is not there is named with its key here, not when a job reads it.
    const auto check_files = [&](const Parameters& values, const std::string& where) {
        if (const auto it = values.find("surface_file"); it != values.end() && !std::filesystem::is_regular_file(s.resolve(it->second)))
            throw Error(fmt::format("{}.surface_file: file not found: {}", where,
                                    printable(s.resolve(it->second).string(), kShownPathChars)));
    };
    check_files(s.parameters, origin + ": parameters");
    if (s.render) check_files(s.render->parameters, origin + ": render.parameters");
    for (const std::vector<Variant>* list : {&s.models, &s.surfaces, &s.lamps})
        for (const Variant& v : *list) check_files(v.parameters, v.origin);
    if (s.slices || s.albedo) {
        if (!root.has("wavelengths")) throw Error(fmt::format("{}: BRDF slices and albedo tables need \"wavelengths\" (nm)", origin));
        s.wavelengths = root["wavelengths"].numbers();
        for (std::size_t i = 0; i < s.wavelengths.size(); ++i)
            if (!(s.wavelengths[i] > 0)) root["wavelengths"][i].error("must be > 0 nm, got {}", s.wavelengths[i]);
    } else if (root.has("wavelengths")) {
        root["wavelengths"].error("are only used by \"brdf_slices\" and \"albedo\"");
    }
    return s;
}

Study read_study(const std::filesystem::path& file) {
    const std::string text = read_input_file(file, "study file");
    const std::filesystem::path folder = file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path();
    return parse_study(text, folder, printable(file.string(), kShownPathChars));
}

std::string to_json(const Study& s) {
    json out;
    const auto variants_json = [&](const std::vector<Variant>& list) {
        json a = json::array();
        for (const Variant& v : list) {
            json e = {{"name", v.name}, {"label", v.label}};
            for (const auto& [k, value] : s.with_absolute_files(v.parameters)) e[k] = value;
            a.push_back(e);
        }
        return a;
    };
    out["models"] = variants_json(s.models);
    if (!s.surfaces.front().name.empty()) out["surfaces"] = variants_json(s.surfaces);
    if (!s.lamps.front().name.empty()) out["lamps"] = variants_json(s.lamps);
    if (!s.parameters.empty()) out["parameters"] = s.with_absolute_files(s.parameters);
    if (s.render) {
        out["scene"] = s.resolve(s.scene).string();
        out["views"] = s.views;
        json r = {{"spp", s.render->spp}, {"overview", s.render->overview}};
        if (s.render->columns > 0) r["columns"] = s.render->columns;
        if (s.render->width) r["width"] = s.render->width;
        if (s.render->height) r["height"] = s.render->height;
        if (s.render->seed) r["seed"] = *s.render->seed;
        if (!s.render->parameters.empty()) r["parameters"] = s.render->parameters;
        if (s.render->crop) r["crop"] = {{"focus", s.render->crop->focus}, {"radius", s.render->crop->radius}};
        out["render"] = r;
    }
    if (!s.wavelengths.empty()) out["wavelengths"] = s.wavelengths;
    if (s.slices) out["brdf_slices"] = {{"theta_i", s.slices->theta_i}, {"phi_i", s.slices->phi_i}};
    if (s.albedo) out["albedo"] = {{"theta_i", s.albedo->theta_i}, {"phi_i", s.albedo->phi_i}};
    return out.dump(2) + "\n";
}

}  // namespace surfscatter::study
