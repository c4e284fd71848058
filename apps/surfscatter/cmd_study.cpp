// surfscatter study: a study file's renders, BRDF slices, albedo tables and comparison sheets, as independent jobs
// over MPI ranks or in this process, resumable (study_runner.hpp; file format in docs/DISTRIBUTED.md).
#include "command.hpp"
#include "study_runner.hpp"

namespace surfscatter::cli {

namespace {

struct StudyArgs {
    std::string file;
    std::string output_dir;
    StudyRunOptions run;
};

const Command command("study", [](CLI::App& app) {
    auto args = std::make_shared<StudyArgs>();
    CLI::App* sub = app.add_subcommand(
        "study", "Run a study file: views x models x surfaces x lamps renders, BRDF slices and albedo tables per "
                 "wavelength, comparison sheets; over MPI ranks under mpirun/srun; resumes where it stopped");
    sub->add_option("study", args->file, "Study file (.json)")->required();
    sub->add_option("-o,--output-dir", args->output_dir, "Folder for outputs and manifest.json (default: the study file's)");
    add_study_run_options(sub, args->run);
    sub->callback([args] {
        run_study(
            [&] {
                study::Study s = study::read_study(args->file);
                if (!args->output_dir.empty()) s.folder = args->output_dir;
                return s;
            },
            args->run);
    });
});

}  // namespace

}  // namespace surfscatter::cli
