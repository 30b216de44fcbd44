#include "JobRunner.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <thread>

extern char** environ;

namespace osgActorRender {

struct JobRunner::Child
{
    pid_t pid = -1;
    int reportFd = -1;  // read end of the child's report pipe
    int errorFd = -1;   // read end of the child's standard error
    std::string reportBuffer;
    std::string errorBuffer;
};

namespace {

/** Hands over every complete line in buffer, keeping the incomplete rest. */
void takeLines(std::string& buffer, const std::function<void(const std::string&)>& onLine)
{
    size_t start = 0;
    for (size_t end; (end = buffer.find('\n', start)) != std::string::npos; start = end + 1)
        onLine(buffer.substr(start, end - start));
    buffer.erase(0, start);
}

/** Reads what is there; false at the end of the stream (or an error), when the descriptor is closed. */
bool readSome(int& fd, std::string& buffer)
{
    char chunk[4096];
    const ssize_t n = read(fd, chunk, sizeof chunk);
    if (n > 0)
    {
        buffer.append(chunk, size_t(n));
        return true;
    }
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) return true;
    close(fd);
    fd = -1;
    return false;
}

/** The environment of a child: this one, with an llvmpipe thread count unless one is set. */
std::vector<std::string> childEnvironment(unsigned numJobs)
{
    std::vector<std::string> environment;
    for (char** variable = environ; *variable != nullptr; ++variable) environment.push_back(*variable);
    if (std::getenv("LP_NUM_THREADS") == nullptr)
    {
        const unsigned processors = std::max(1u, std::thread::hardware_concurrency());
        environment.push_back("LP_NUM_THREADS=" + std::to_string(std::max(1u, processors / numJobs)));
    }
    return environment;
}

std::vector<char*> pointersTo(std::vector<std::string>& strings)
{
    std::vector<char*> pointers;
    for (std::string& text : strings) pointers.push_back(&text[0]);
    pointers.push_back(nullptr);
    return pointers;
}

} // namespace

JobRunner::JobRunner(const std::vector<std::string>& arguments, unsigned numJobs)
    : _arguments(arguments), _numJobs(numJobs), _worstStatus(0)
{
    // The program's own file, read through the link rather than executed through it: the path is the same, but
    // tools that run the program (valgrind) answer the read with the program and would have the link run them.
    char path[4096];
    const ssize_t length = readlink("/proc/self/exe", path, sizeof path - 1);
    _program = length > 0 ? std::string(path, size_t(length)) : std::string("/proc/self/exe");
}

bool JobRunner::start(unsigned part, Child& child, std::string& error)
{
    int report[2];
    int errors[2];
    if (pipe2(report, O_CLOEXEC) != 0)
    {
        error = std::string("cannot make a pipe for a job: ") + std::strerror(errno);
        return false;
    }
    if (pipe2(errors, O_CLOEXEC) != 0)
    {
        error = std::string("cannot make a pipe for a job: ") + std::strerror(errno);
        close(report[0]);
        close(report[1]);
        return false;
    }

    // Everything the child needs is made before fork(): between fork() and exec() only async-signal-safe calls.
    std::vector<std::string> argv{"osgactorrender"};
    argv.insert(argv.end(), _arguments.begin(), _arguments.end());
    argv.insert(argv.end(), {"--part", std::to_string(part) + "/" + std::to_string(_numJobs), "--job-report-fd",
                             std::to_string(report[1])});
    std::vector<std::string> environment = childEnvironment(_numJobs);
    std::vector<char*> argvPointers = pointersTo(argv);
    std::vector<char*> environmentPointers = pointersTo(environment);
    static const char kExecFailed[] = "osgactorrender: cannot start a job\n";

    const std::string program = _program;
    child.pid = fork();
    if (child.pid == 0)
    {
        // The report descriptor stays open across exec() (its number is on the command line); the others close.
        if (dup2(errors[1], STDERR_FILENO) < 0 || fcntl(report[1], F_SETFD, 0) != 0) _exit(2);
        execve(program.c_str(), argvPointers.data(), environmentPointers.data());
        const ssize_t ignored = write(STDERR_FILENO, kExecFailed, sizeof kExecFailed - 1);
        (void)ignored;
        _exit(2);
    }
    close(report[1]);
    close(errors[1]);
    if (child.pid < 0)
    {
        error = std::string("cannot start a job: ") + std::strerror(errno);
        close(report[0]);
        close(errors[0]);
        return false;
    }
    child.reportFd = report[0];
    child.errorFd = errors[0];
    return true;
}

void JobRunner::addMessage(const std::string& line)
{
    if (!line.empty() && std::find(_messages.begin(), _messages.end(), line) == _messages.end())
        _messages.push_back(line);
}

void JobRunner::pump(std::vector<Child>& children, const std::function<void(const std::string&)>& onReport)
{
    for (;;)
    {
        std::vector<pollfd> fds;
        std::vector<std::pair<Child*, bool>> owners; // the child, and whether the descriptor is its report
        for (Child& child : children)
        {
            if (child.reportFd >= 0)
            {
                fds.push_back({child.reportFd, POLLIN, 0});
                owners.emplace_back(&child, true);
            }
            if (child.errorFd >= 0)
            {
                fds.push_back({child.errorFd, POLLIN, 0});
                owners.emplace_back(&child, false);
            }
        }
        if (fds.empty()) return;
        if (poll(fds.data(), fds.size(), -1) < 0)
        {
            if (errno == EINTR) continue;
            return;
        }
        for (size_t i = 0; i < fds.size(); ++i)
        {
            if (fds[i].revents == 0) continue;
            Child& child = *owners[i].first;
            if (owners[i].second)
            {
                readSome(child.reportFd, child.reportBuffer);
                takeLines(child.reportBuffer, onReport);
            }
            else
            {
                readSome(child.errorFd, child.errorBuffer);
                takeLines(child.errorBuffer, [this](const std::string& line) { addMessage(line); });
            }
        }
    }
}

bool JobRunner::run(const std::function<void(const std::string& line)>& onReport, std::string& error)
{
    std::vector<Child> children(_numJobs);
    bool started = true;
    for (unsigned part = 1; part <= _numJobs && started; ++part) started = start(part, children[part - 1], error);

    pump(children, onReport);
    for (unsigned part = 1; part <= _numJobs; ++part)
    {
        Child& child = children[part - 1];
        addMessage(child.errorBuffer); // a last line without a newline
        if (child.pid <= 0) continue;
        int status = 0;
        while (waitpid(child.pid, &status, 0) < 0 && errno == EINTR) {}
        if (WIFEXITED(status)) _worstStatus = std::max(_worstStatus, std::min(WEXITSTATUS(status), 2));
        else
        {
            _worstStatus = 2;
            addMessage("osgactorrender: job " + std::to_string(part) + "/" + std::to_string(_numJobs) +
                       " ended by signal " + std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0));
        }
    }
    if (!started) _worstStatus = 2;
    return started;
}

} // namespace osgActorRender
