#pragma once
#include <algorithm>
#include <cmath>
#include <map>
#include <filesystem>
#include <memory>
#include <string>

#include "surfscatter/core/error.hpp"
#include "surfscatter/render/integrator.hpp"
#include "surfscatter/render/xml_loader.hpp"

namespace surfscatter::render::test {

// A scene with a camera at `origin` looking at `target`, a small film and the given body.
inline std::string scene_xml(const std::string& body, const std::string& origin = "0, 0, 3",
                             const std::string& target = "0, 0, 0", double fov = 1.0, int size = 8,
                             const std::string& integrator = "<integrator type=\"path\"/>") {
    return "<scene version=\"3.0.0\">\n" + integrator +
           "\n<sensor type=\"perspective\">\n"
           "  <float name=\"fov\" value=\"" + std::to_string(fov) + "\"/>\n"
           "  <transform name=\"to_world\"><lookat origin=\"" + origin + "\" target=\"" + target +
           "\" up=\"0, 1, 0\"/></transform>\n"
           "  <film type=\"hdrfilm\"><integer name=\"width\" value=\"" + std::to_string(size) +
           "\"/><integer name=\"height\" value=\"" + std::to_string(size) +
           "\"/><rfilter type=\"box\"/></film>\n"
           "  <sampler type=\"independent\"><integer name=\"sample_count\" value=\"16\"/></sampler>\n"
           "</sensor>\n" + body + "\n</scene>\n";
}

// Mean Y over the film and its standard error (pixels as independent estimates).
struct MeanY {
    double mean = 0;
    double standard_error = 0;
};

inline MeanY mean_y(const Film& film) {
    double sum = 0, sum2 = 0;
    const int n = film.width() * film.height();
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const double v = film.xyz(x, y).y;
            sum += v;
            sum2 += v * v;
        }
    MeanY m;
    m.mean = sum / n;
    m.standard_error = std::sqrt(std::max(0.0, sum2 / n - m.mean * m.mean) / (n - 1));
    return m;
}

inline Film render_string(const std::string& xml, int spp, int threads = 0, std::uint64_t seed = 1) {
    auto scene = load_scene_from_string(xml, "test.xml");
    RenderOptions options;
    options.spp = spp;
    options.threads = threads;
    options.seed = seed;
    options.progress = false;
    return render(*scene, options);
}

// Mean Y over the film, averaged over renders with seeds 1..seeds; the standard error is that of the seed average,
// i.e. Monte Carlo noise only (the spread between pixels is image content, not noise).
inline MeanY mean_y_over_seeds_of(const Scene& scene, int spp, int seeds) {
    double sum = 0, sum2 = 0;
    for (int s = 1; s <= seeds; ++s) {
        RenderOptions options;
        options.spp = spp;
        options.seed = static_cast<std::uint64_t>(s);
        options.progress = false;
        const double m = mean_y(render(scene, options)).mean;
        sum += m;
        sum2 += m * m;
    }
    MeanY out;
    out.mean = sum / seeds;
    out.standard_error = std::sqrt(std::max(0.0, sum2 / seeds - out.mean * out.mean) / (seeds - 1));
    return out;
}

inline MeanY mean_y_over_seeds(const std::string& xml, int spp, int seeds) {
    return mean_y_over_seeds_of(*load_scene_from_string(xml, "test.xml"), spp, seeds);
}

// A BSDF built by the XML loader (on a rectangle of an otherwise empty scene), for tests of the material itself.
struct LoadedMaterial {
    std::unique_ptr<Scene> scene;
    const Material* material = nullptr;
};
inline LoadedMaterial load_material(const std::string& bsdf_xml, const std::filesystem::path& where = "test.xml") {
    LoadedMaterial m;
    m.scene = load_scene_from_string(scene_xml("<shape type=\"rectangle\">" + bsdf_xml + "</shape>"), where);
    m.material = m.scene->material(0);
    return m;
}

// The message of the Error that loading `xml` throws ("" if it loads).
inline std::string load_error(const std::string& xml, const std::map<std::string, std::string>& defines = {}) {
    try {
        load_scene_from_string(xml, "scene.xml", defines);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// 1-based line of the first occurrence of `needle` in `text`.
inline int line_of(const std::string& text, const std::string& needle) {
    const auto pos = text.find(needle);
    return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

// A fresh directory under the system temporary directory.
inline std::filesystem::path temp_dir(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("surfscatter_" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace surfscatter::render::test
