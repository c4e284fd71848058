#pragma once
#include <string>

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
inline MeanY mean_y_over_seeds(const std::string& xml, int spp, int seeds) {
    double sum = 0, sum2 = 0;
    for (int s = 1; s <= seeds; ++s) {
        const double m = mean_y(render_string(xml, spp, 0, static_cast<std::uint64_t>(s))).mean;
        sum += m;
        sum2 += m * m;
    }
    MeanY out;
    out.mean = sum / seeds;
    out.standard_error = std::sqrt(std::max(0.0, sum2 / seeds - out.mean * out.mean) / (seeds - 1));
    return out;
}

}  // namespace surfscatter::render::test
