#include "surfscatter/render/model_parameters.hpp"

#include <cmath>
#include <set>

#include "surfscatter/bsdf/factory.hpp"

namespace surfscatter::render {

namespace {

// Properties over name = value text: scalars and file names only (what surfscatter's BSDF plugins read).
class TextProperties final : public Properties {
public:
    TextProperties(const std::map<std::string, std::string>& values, std::string origin, std::vector<std::string>* notes)
        : values_(values), origin_(std::move(origin)), notes_(notes) {}

    std::string where() const override { return origin_; }
    std::string where(const std::string& name) const override { return origin_ + ": " + name; }
    bool has(const std::string& name) const override { return values_.count(name) != 0; }

    double get_float(const std::string& name, double fallback) override {
        const std::string* text = find(name);
        if (!text) return fallback;
        std::size_t used = 0;
        double v = 0;
        try {
            v = std::stod(*text, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != text->size() || !std::isfinite(v)) fail_param(name, "'{}' is not a finite number", *text);
        return v;
    }
    double get_float_required(const std::string& name) override {
        if (!has(name)) fail("needs the parameter '{}'", name);
        return get_float(name, 0);
    }
    int get_int(const std::string& name, int fallback) override {
        if (!has(name)) return fallback;
        const double v = get_float(name, 0);
        if (v != std::floor(v) || std::abs(v) > 2e9) fail_param(name, "'{}' is not an integer", v);
        return static_cast<int>(v);
    }
    bool get_bool(const std::string& name, bool fallback) override {
        const std::string* text = find(name);
        if (!text) return fallback;
        if (*text == "true") return true;
        if (*text == "false") return false;
        fail_param(name, "boolean must be true or false, got '{}'", *text);
    }
    std::string get_string(const std::string& name, const std::string& fallback) override {
        const std::string* text = find(name);
        return text ? *text : fallback;
    }
    std::optional<std::variant<double, std::string>> get_float_or_string(const std::string& name) override {
        const std::string* text = find(name);
        if (!text) return std::nullopt;
        return *text;
    }
    std::filesystem::path get_file(const std::string& name) override {
        const std::string* text = find(name);
        if (!text) fail("needs the parameter '{}'", name);
        if (!std::filesystem::exists(*text)) fail_param(name, "file not found: {}", *text);
        return *text;
    }
    std::optional<Vec3> get_point(const std::string& name) override { return unsupported<std::optional<Vec3>>(name); }
    Transform get_transform(const std::string& name) override { return unsupported<Transform>(name); }
    TexturePtr get_texture(const std::string& name, double) override { return unsupported<TexturePtr>(name); }
    TexturePtr get_texture_required(const std::string& name) override { return unsupported<TexturePtr>(name); }
    SpectrumPtr get_spectrum(const std::string& name, bool, std::optional<double>) override {
        return unsupported<SpectrumPtr>(name);
    }
    std::vector<MaterialPtr> take_bsdfs() override { return {}; }
    std::vector<TexturePtr> take_textures() override { return {}; }
    void share_height_map(bsdf::SurfaceOptions& surface) override {
        if (surface.psd == bsdf::PsdKind::file && !surface.prepared) bsdf::load_height_map(surface);
    }
    void add_note(const std::string& note) override {
        if (notes_) notes_->push_back(note);
    }

    // Names given but never read.
    std::vector<std::string> unused() const {
        std::vector<std::string> out;
        for (const auto& [name, value] : values_)
            if (!read_.count(name)) out.push_back(name);
        return out;
    }

private:
    const std::string* find(const std::string& name) {
        const auto it = values_.find(name);
        if (it == values_.end()) return nullptr;
        read_.insert(name);
        return &it->second;
    }
    template <typename T>
    T unsupported(const std::string& name) {
        fail_param(name, "cannot be given as text");
    }

    const std::map<std::string, std::string>& values_;
    std::string origin_;
    std::vector<std::string>* notes_;
    std::set<std::string> read_;
};

}  // namespace

bsdf::ModelOptions scattering_model_options(const std::string& type, const std::map<std::string, std::string>& parameters,
                                            const std::string& origin, std::vector<std::string>* notes) {
    TextProperties props(parameters, origin, notes);
    const bsdf::ModelOptions options = scattering_model_options(props, type);
    for (const std::string& name : props.unused()) props.fail("'{}' is not a parameter of bsdf '{}'", name, type);
    return options;
}

}  // namespace surfscatter::render
