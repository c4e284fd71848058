#pragma once
// A command started in the background (its own process group, stdout and stderr to files), for end-to-end tests
// that signal it (Ctrl-C), kill one of its children (an MPI rank) or wait for it with a deadline.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace surfscatter::test {

class BackgroundProcess {
public:
    BackgroundProcess(const std::vector<std::string>& argv, const std::filesystem::path& out,
                      const std::filesystem::path& err)
        : out_(out), err_(err) {
        // Emptied before the child starts, so that nothing an earlier run wrote is read as this one's.
        std::ofstream(out, std::ios::trunc).close();
        std::ofstream(err, std::ios::trunc).close();
        pid_ = fork();
        if (pid_ == 0) {
            setpgid(0, 0);
            const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            const int in = open("/dev/null", O_RDONLY);
            dup2(o, 1);
            dup2(e, 2);
            dup2(in, 0);
            std::vector<char*> args;
            for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
            args.push_back(nullptr);
            execvp(args[0], args.data());
            _exit(127);
        }
    }
    ~BackgroundProcess() {
        if (!finished_) {
            kill(-pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
        }
    }
    BackgroundProcess(const BackgroundProcess&) = delete;
    BackgroundProcess& operator=(const BackgroundProcess&) = delete;

    pid_t pid() const { return pid_; }
    void signal(int sig) const { kill(pid_, sig); }

    // Exit status, or -1 if it did not end within `seconds` (then it and its process group are killed), or
    // 128 + the signal that ended it.
    int wait(double seconds) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        while (std::chrono::steady_clock::now() < deadline) {
            if (poll()) return status_;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        kill(-pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
        finished_ = true;
        return -1;
    }

    bool running() { return !poll(); }

    // Processes whose parent is this one (an MPI launcher's ranks on this host).
    std::vector<pid_t> children() const {
        std::vector<pid_t> out;
        for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
            const std::string name = entry.path().filename().string();
            if (name.find_first_not_of("0123456789") != std::string::npos) continue;
            std::ifstream stat(entry.path() / "stat");
            std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
            const auto close = text.rfind(')');
            if (close == std::string::npos) continue;
            char state = 0;
            long parent = 0;
            if (std::sscanf(text.c_str() + close + 1, " %c %ld", &state, &parent) == 2 && parent == pid_)
                out.push_back(static_cast<pid_t>(std::stol(name)));
        }
        return out;
    }

    std::string err() const { return read(err_); }
    std::string out() const { return read(out_); }

private:
    bool poll() {
        if (finished_) return true;
        int status = 0;
        if (waitpid(pid_, &status, WNOHANG) != pid_) return false;
        finished_ = true;
        status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        return true;
    }
    static std::string read(const std::filesystem::path& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    }

    std::filesystem::path out_, err_;
    pid_t pid_ = -1;
    bool finished_ = false;
    int status_ = -1;
};

}  // namespace surfscatter::test
