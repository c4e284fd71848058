#include "surfscatter/core/output_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <set>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/paths.hpp"

namespace surfscatter {

namespace fs = std::filesystem;

namespace {

// The file a path names once "..", "." and symbolic links are resolved (as far as it exists), absolute.
fs::path resolved(const fs::path& path) {
    std::error_code ec;
    fs::path absolute = fs::absolute(path, ec);
    if (ec) absolute = path;
    fs::path canonical = fs::weakly_canonical(absolute, ec);
    return ec ? absolute.lexically_normal() : canonical;
}

// Whether two resolved paths are one file: the same name, or (both existing) the same device and inode - a hard
// link, or a folder reached by a bind mount.
bool same_file(const fs::path& a, const fs::path& b) {
    if (a == b) return true;
    struct stat sa {}, sb {};
    return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

// fsync of a file (or folder) by name: a delayed write error (a full disk, a network file system) shows here.
int sync_path(const fs::path& path, int flags) {
    const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
    if (fd < 0) return errno;
    const int error = ::fsync(fd) == 0 ? 0 : errno;
    return ::close(fd) == 0 || error != 0 ? error : errno;
}

void remove_quietly(const fs::path& path) {
    std::error_code ec;
    fs::remove(path, ec);
}

// `message` with every occurrence of the temporary file's name replaced by the output's.
std::string naming_output(std::string message, const fs::path& temporary, const fs::path& output) {
    const std::string from = temporary.string(), to = output.string();
    for (std::size_t at = message.find(from); !from.empty() && at != std::string::npos; at = message.find(from, at + to.size()))
        message.replace(at, from.size(), to);
    return message;
}

}  // namespace

std::string printable_path(const fs::path& path) { return printable(path.string(), kShownPathChars); }

fs::path temporary_beside(const fs::path& file) {
    static const unsigned host = static_cast<unsigned>(std::hash<std::string>{}(host_name()) & 0xffffff);
    static std::atomic<unsigned> calls{0};
    std::string extension = file.extension().string();
    if (extension.size() > 12) extension.clear();  // no format has so long an extension
    return file.parent_path() /
           fmt::format(".ss-{:06x}-{:x}-{}{}", host, static_cast<unsigned long>(getpid()), ++calls, extension);
}

OutputFiles::~OutputFiles() {
    for (const Entry& e : entries_)
        if (e.written) remove_quietly(e.temporary);
}

void OutputFiles::input(const fs::path& path, const std::string& what) {
    std::error_code ec;
    if (path.empty() || !fs::exists(path, ec)) return;
    entries_.push_back({path, resolved(path), {}, what, true, false});
}

fs::path OutputFiles::refuse_collisions(const fs::path& path, const std::string& what) const {
    if (path.empty()) fail("{} is empty: name a file", what);
    const fs::path destination = resolved(path);
    for (const Entry& e : entries_)
        if (same_file(destination, e.destination)) {
            if (e.input)
                fail("{} {} would replace the input {} {}: name another output", what, printable_path(path), e.what, printable_path(e.given));
            fail("{} {} and {} {} are the same file: name another output", what, printable_path(path), e.what, printable_path(e.given));
        }
    return destination;
}

void OutputFiles::plan(const fs::path& path, const std::string& what) {
    entries_.push_back({path, refuse_collisions(path, what), {}, what, false, false});
}

void OutputFiles::output(const fs::path& path, const std::string& what) {
    const fs::path destination = refuse_collisions(path, what);
    std::error_code ec;
    const fs::file_status status = fs::status(destination, ec);
    if (fs::is_directory(status)) fail("{} {} is a folder: name a file in it", what, printable_path(path));
    if (fs::exists(status) && !fs::is_regular_file(status))
        fail("{} {} is not a regular file (a device, FIFO or socket): name a file", what, printable_path(path));
    const fs::path folder = destination.parent_path();
    const std::string shown_folder = printable_path(path.has_parent_path() ? path.parent_path() : fs::path("."));
    if (!fs::is_directory(folder, ec))
        fail("cannot write {} {}: folder {} {}", what, printable_path(path), shown_folder,
             fs::exists(folder, ec) ? "is not a folder" : "does not exist");
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        fail("cannot write {} {}: folder {}: {}", what, printable_path(path), shown_folder, std::strerror(errno));
    // A derived name (-o's .json beside a .csv) can pass the limit its output kept to: refused here, not at commit().
    const long name_max = ::pathconf(folder.c_str(), _PC_NAME_MAX);
    if (name_max > 0 && destination.filename().string().size() > static_cast<std::size_t>(name_max))
        fail("cannot write {} {}: its name is longer than the {} bytes the file system allows", what,
             printable_path(path), name_max);
    entries_.push_back({path, destination, {}, what, false, false});
}

OutputFiles::Entry& OutputFiles::find_output(const fs::path& path) {
    const auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return !e.input && e.given == path; });
    if (it == entries_.end()) throw std::logic_error("output not declared: " + path.string());
    return *it;
}

const OutputFiles::Entry& OutputFiles::find_output(const fs::path& path) const {
    return const_cast<OutputFiles*>(this)->find_output(path);
}

void OutputFiles::write(const fs::path& path, const std::string& text) {
    write_with(path, [&](const fs::path& temporary) {
        const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) fail("cannot write {}: {}", printable_path(temporary), std::strerror(errno));
        int error = 0;
        for (std::size_t done = 0; done < text.size() && error == 0;) {
            const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
            if (n > 0) done += static_cast<std::size_t>(n);
            else if (errno != EINTR) error = errno;
        }
        if (::close(fd) != 0 && error == 0) error = errno;
        if (error != 0) fail("cannot write {}: {}", printable_path(temporary), std::strerror(error));
    });
}

void OutputFiles::write_with(const fs::path& path, const std::function<void(const fs::path&)>& writer) {
    write_together({path}, [&](const std::vector<fs::path>& temporary) { writer(temporary[0]); });
}

void OutputFiles::write_together(const std::vector<fs::path>& paths,
                                 const std::function<void(const std::vector<fs::path>&)>& writer) {
    std::vector<Entry*> outputs;
    std::vector<fs::path> temporary;
    for (const fs::path& path : paths) {
        Entry& e = find_output(path);
        if (e.written) remove_quietly(e.temporary);
        e.written = false;
        e.temporary = temporary_beside(e.destination);
        outputs.push_back(&e);
        temporary.push_back(e.temporary);
    }
    const auto give_up = [&](std::string message) {
        for (const Entry* e : outputs) {
            remove_quietly(e->temporary);
            message = naming_output(message, e->temporary, e->given);
        }
        throw Error(message);
    };
    try {
        writer(temporary);
    } catch (const Error& error) {
        give_up(error.what());
    } catch (const fs::filesystem_error& error) {
        give_up(fmt::format("cannot write {}: {}", printable_path(error.path1()), error.code().message()));
    }
    for (const Entry* e : outputs) {
        std::error_code ec;
        if (!fs::is_regular_file(e->temporary, ec)) give_up(fmt::format("cannot write {}: nothing was written", printable_path(e->given)));
        if (const int error = sync_path(e->temporary, O_RDONLY); error != 0)
            give_up(fmt::format("cannot write {}: {}", printable_path(e->given), std::strerror(error)));
    }
    for (Entry* e : outputs) e->written = true;
}

const fs::path& OutputFiles::staged(const fs::path& path) const {
    const Entry& e = find_output(path);
    if (!e.written) throw std::logic_error("output not written yet: " + path.string());
    return e.temporary;
}

void OutputFiles::commit() {
    std::vector<Entry*> pending;
    for (Entry& e : entries_)
        if (e.written) pending.push_back(&e);
    // A set of outputs lands together: before the first rename, each old file of a set of several is kept under a
    // temporary name (a hard link, else a copy), so that a rename failing midway can put back the ones done before.
    std::vector<fs::path> kept(pending.size());
    const auto drop_kept = [&](std::size_t from) {
        for (std::size_t i = from; i < kept.size(); ++i)
            if (!kept[i].empty()) remove_quietly(kept[i]);
    };
    for (std::size_t i = 0; pending.size() > 1 && i < pending.size(); ++i) {
        const Entry& e = *pending[i];
        std::error_code ec;
        if (!fs::is_regular_file(e.destination, ec)) continue;  // none (or a folder put there since: its rename fails)
        kept[i] = temporary_beside(e.destination);
        if (::link(e.destination.c_str(), kept[i].c_str()) == 0) continue;
        fs::copy_file(e.destination, kept[i], ec);  // a file system without hard links
        if (ec) {
            drop_kept(0);
            fail("cannot write {}: its old file cannot be kept until the set is in place: {}", printable_path(e.given), ec.message());
        }
    }
    std::set<fs::path> folders;
    for (std::size_t i = 0; i < pending.size(); ++i) {
        Entry& e = *pending[i];
        std::error_code ec;
        fs::rename(e.temporary, e.destination, ec);
        if (ec) {
            // The outputs moved before this one go back to their old files (or away, where there were none); the
            // temporary files of the rest go.
            std::string message = fmt::format("cannot move {} into place: {}", printable_path(e.given), ec.message());
            for (std::size_t j = 0; j < i; ++j) {
                Entry& done = *pending[j];
                done.written = false;
                std::error_code back;
                if (kept[j].empty()) fs::remove(done.destination, back);
                else fs::rename(kept[j], done.destination, back);
                if (back)
                    message += fmt::format("; {} could not be put back ({}){}", printable_path(done.given), back.message(),
                                           kept[j].empty() ? "" : ": its old file is " + printable_path(kept[j]));
            }
            for (std::size_t j = i; j < pending.size(); ++j) {
                remove_quietly(pending[j]->temporary);
                pending[j]->written = false;
            }
            drop_kept(i);
            throw Error(message);
        }
        folders.insert(e.destination.parent_path());
    }
    for (Entry* e : pending) e->written = false;
    drop_kept(0);
    for (const fs::path& folder : folders) sync_path(folder, O_RDONLY | O_DIRECTORY);  // the renames, best effort
}

void write_atomically(const fs::path& file, const std::function<void(const fs::path&)>& writer) {
    OutputFiles files;
    files.output(file, "output");
    files.write_with(file, writer);
    files.commit();
}

void write_file_atomically(const fs::path& file, const std::string& text) {
    OutputFiles files;
    files.output(file, "output");
    files.write(file, text);
    files.commit();
}

}  // namespace surfscatter
