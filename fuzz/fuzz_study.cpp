// Fuzz target: study files and manifests (study/study.hpp, study/manifest.hpp, through study/json_input.hpp). The
// bytes are parsed as a study file; a study that parses is expanded into its jobs, written back (to_json) and parsed
// again, which must give the same jobs. Then the same bytes are read as the manifest of a small fixed study and
// every job is asked whether it is up to date.
#include <vector>

#include "fuzz_common.hpp"
#include "surfscatter/study/jobs.hpp"
#include "surfscatter/study/manifest.hpp"
#include "surfscatter/study/study.hpp"

namespace {

using namespace surfscatter;

// Jobs of a study, unless there would be so many that expanding them is the fuzzer's whole time.
std::vector<study::Job> jobs_of(const study::Study& s) {
    const std::size_t views = s.render ? s.views.size() : 1, wavelengths = std::max<std::size_t>(s.wavelengths.size(), 1);
    if (s.models.size() * s.surfaces.size() * s.lamps.size() * views * wavelengths > 20000) return {};
    return study::expand(s);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(fuzz::as_text(data, size));
    fuzz::expect_clean([&] {
        const study::Study s = study::parse_study(text, fuzz::scratch(), "fuzz.json");
        const std::vector<study::Job> jobs = jobs_of(s);
        const study::Study again = study::parse_study(study::to_json(s), fuzz::scratch(), "again.json");
        const std::vector<study::Job> jobs_again = jobs_of(again);
        FUZZ_CHECK(jobs_again.size() == jobs.size());
        for (std::size_t i = 0; i < jobs.size(); ++i) FUZZ_CHECK(jobs_again[i].id == jobs[i].id);
    });
    static const study::Study fixed = study::parse_study(
        R"({"models": [{"name": "a", "model": "ggx", "alpha": 0.1}], "wavelengths": [500, 600],
            "albedo": {"theta_i": [0, 30]}, "brdf_slices": {"theta_i": [45]}})",
        fuzz::scratch(), "fixed.json");
    static const std::vector<study::Job> fixed_jobs = study::expand(fixed);
    const auto manifest = fuzz::write_input("manifest.json", text);
    fuzz::expect_clean([&] {
        const study::Manifest m(manifest, fixed_jobs, fuzz::scratch());
        for (const study::Job& job : fixed_jobs) (void)m.up_to_date(job);
    });
    return 0;
}
