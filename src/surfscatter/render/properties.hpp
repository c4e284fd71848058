#pragma once
// The parameters of one plugin element of a scene file, as Mitsuba's Properties: typed look-ups by the names the
// scene uses (<float name="int_ior" .../>), each remembered as used so that the loader can report every parameter a
// plugin did not read as an error. Every plugin factory (bsdfs/, emitters/, filters/, ...) builds its object from a
// Properties; errors name the scene file and line of the element or of the offending parameter.
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <fmt/format.h>

#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/material.hpp"
#include "surfscatter/render/spectrum_source.hpp"
#include "surfscatter/render/texture.hpp"
#include "surfscatter/render/transform.hpp"

namespace surfscatter::render {

// An Error whose message already starts with the scene file and line; the loader adds the location of the element
// being built to any other Error (xml_loader.cpp), so every scene error names its file:line exactly once.
class SceneError : public Error {
public:
    using Error::Error;
};

class Properties {
public:
    virtual ~Properties() = default;

    // "file:line" of the plugin element, or of the parameter `name` if the element has it.
    virtual std::string where() const = 0;
    virtual std::string where(const std::string& name) const = 0;
    // Throw Error("file:line: message") for the element or for one of its parameters.
    template <typename... Args>
    [[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) const {
        throw SceneError(where() + ": " + fmt::format(format, std::forward<Args>(args)...));
    }
    template <typename... Args>
    [[noreturn]] void fail_param(const std::string& name, fmt::format_string<Args...> format, Args&&... args) const {
        throw SceneError(where(name) + ": " + fmt::format(format, std::forward<Args>(args)...));
    }

    virtual bool has(const std::string& name) const = 0;

    // Scalars: <float>/<integer>, <integer>, <boolean>, <string>. A missing parameter gives `fallback`.
    virtual double get_float(const std::string& name, double fallback) = 0;
    virtual double get_float_required(const std::string& name) = 0;
    virtual int get_int(const std::string& name, int fallback) = 0;
    virtual bool get_bool(const std::string& name, bool fallback) = 0;
    virtual std::string get_string(const std::string& name, const std::string& fallback) = 0;
    // A parameter given either as <float> or as <string> (an index of refraction by value or by name).
    virtual std::optional<std::variant<double, std::string>> get_float_or_string(const std::string& name) = 0;
    // <point> or <vector>.
    virtual std::optional<Vec3> get_point(const std::string& name) = 0;
    // <transform>; the identity when absent.
    virtual Transform get_transform(const std::string& name) = 0;
    // A <string> file name resolved against the scene file's directory; the file must exist.
    virtual std::filesystem::path get_file(const std::string& name) = 0;

    // <float>, <spectrum>, <rgb>, a nested <texture> or a <ref> to one; a constant `fallback` when absent.
    virtual TexturePtr get_texture(const std::string& name, double fallback) = 0;
    virtual TexturePtr get_texture_required(const std::string& name) = 0;
    // <float>, <spectrum> or <rgb>; `illuminant` selects the emission variant of RGB upsampling (times D65).
    virtual SpectrumPtr get_spectrum(const std::string& name, bool illuminant, std::optional<double> fallback) = 0;

    // The nested <bsdf> elements and unnamed <ref>s to BSDFs, in document order.
    virtual std::vector<MaterialPtr> take_bsdfs() = 0;
    // The nested <texture> elements and <ref>s to textures not read as named parameters so far (bumpmap's height
    // map may carry any name, as in Mitsuba).
    virtual std::vector<TexturePtr> take_textures() = 0;

    // A surface_file height map (psd file or measured) is read once per scene, however many BSDFs use it, and
    // reported in the scene's notes; this sets surface.height_map to the shared copy.
    virtual void share_height_map(bsdf::SurfaceOptions& surface) = 0;
    // A note for the user about this object (e.g. how a measured PSD is extrapolated), with its file and line.
    virtual void add_note(const std::string& note) = 0;
};

}  // namespace surfscatter::render
