#pragma once
// Writing the user's output files safely (docs/RELIABILITY.md, "Outputs"): an output never replaces an input or
// another output of the same run, each file is written under a short temporary name beside it, flushed, synced and
// checked, and a run's outputs are renamed into place together, after every one of them was written; a failure
// leaves the old files (or none), never part of one, and no temporary file.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace surfscatter {

// A file name as the messages and notes about outputs show it: printable(path, kShownPathChars).
std::string printable_path(const std::filesystem::path& path);

// A temporary name beside `file` that no other process, host or call uses, keeping the extension (tools pick the
// format from it): folder/.ss-<host>-<pid>-<n><.ext>, at most 40 bytes, so that a file whose own name has the
// maximum length (255 bytes) still has one.
std::filesystem::path temporary_beside(const std::filesystem::path& file);

class OutputFiles {
public:
    OutputFiles() = default;
    OutputFiles(const OutputFiles&) = delete;
    OutputFiles& operator=(const OutputFiles&) = delete;
    // Removes the temporary files of outputs not committed.
    ~OutputFiles();

    // An input the outputs must not replace; `what` names it as the user gave it ("--profile"). A path that is
    // empty or names nothing is skipped (reading it fails on its own).
    void input(const std::filesystem::path& path, const std::string& what);

    // Declares an output before any work: an Error naming both if it resolves to an input or to an output declared
    // before (same path after resolving "..", symbolic links and hard links), if its folder is missing or not
    // writable, or if it exists as something other than a regular file. `what` names it ("-o", "the CSV beside
    // --plot"). Every file a command writes is declared, derived names too.
    void output(const std::filesystem::path& path, const std::string& what);

    // Declares a file that a later step writes, into folders it may create (a study's job outputs, checked when
    // the study is expanded): refused, as output() refuses, if it resolves to an input or to a file planned or
    // declared before; its folder is not checked (the step that writes it declares it again, with output()).
    void plan(const std::filesystem::path& path, const std::string& what);

    // Writes a declared output's contents to its temporary file, checked and synced to disk.
    void write(const std::filesystem::path& path, const std::string& text);
    // The same through `writer(temporary path)` (a library writer, a plot script): the file it leaves is synced
    // and checked; an Error it throws names the output instead of the temporary file.
    void write_with(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& writer);
    // The same for a writer that writes several outputs at once (a render's EXR and PNG): their temporary paths in
    // the order of `paths`.
    void write_together(const std::vector<std::filesystem::path>& paths,
                        const std::function<void(const std::vector<std::filesystem::path>&)>& writer);

    // Where a written output waits until commit() (a plot script reads the CSV written before it).
    const std::filesystem::path& staged(const std::filesystem::path& path) const;

    // Renames every written output into place (then none is pending). If a rename fails, the outputs renamed before
    // it get their old files back (kept under a temporary name until all are in place), so that no new file stays
    // beside an old one of the same set; the Error names the output that failed.
    void commit();

private:
    struct Entry {
        std::filesystem::path given, destination, temporary;
        std::string what;
        bool input = false, written = false;
    };
    // The resolved path, after the Error naming both if it is one file with an entry before.
    std::filesystem::path refuse_collisions(const std::filesystem::path& path, const std::string& what) const;
    Entry& find_output(const std::filesystem::path& path);
    const Entry& find_output(const std::filesystem::path& path) const;
    std::vector<Entry> entries_;
};

// Writes `file` through `writer(temporary path)`, or `text` to it, as a one-file OutputFiles does (the library's
// writers: images, height maps, camera files); throws Error naming the file if it cannot.
void write_atomically(const std::filesystem::path& file, const std::function<void(const std::filesystem::path&)>& writer);
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

}  // namespace surfscatter
