/* osgactorrender --jobs: the frames spread over child processes of this program, one contiguous part each. */
#ifndef OSGACTORRENDER_JOBRUNNER_H
#define OSGACTORRENDER_JOBRUNNER_H 1

#include <functional>
#include <string>
#include <vector>

namespace osgActorRender {

/** Runs this program (the file /proc/self/exe names) numJobs times at once, child k with "--part k/numJobs --job-report-fd n"
  * appended to the command line given, so that each renders its own part on its own OSMesa context. A child
  * reports each frame as a line on that descriptor; the runner hands every line over as it comes (the parent's
  * progress bar counts them) and keeps what the children write on their standard error, each line once.
  *
  * Unless LP_NUM_THREADS is set, each child's llvmpipe gets an equal share of the processors (at least one
  * rasterizer thread): the children already keep them busy. llvmpipe's images do not depend on its thread count. */
class JobRunner
{
public:
    /** arguments: the command line of every child, without its program name or --jobs. */
    JobRunner(const std::vector<std::string>& arguments, unsigned numJobs);

    /** Starts the children and returns once all of them have ended; false, with the reason, if one could not be
      * started (those started are still waited for). */
    bool run(const std::function<void(const std::string& line)>& onReport, std::string& error);

    /** The worst exit: 0 every child succeeded, 1 one found a frame that differs, 2 one failed or crashed. */
    int getWorstStatus() const { return _worstStatus; }
    /** The children's standard error, each distinct line once, in the order they came. */
    const std::vector<std::string>& getMessages() const { return _messages; }

private:
    struct Child;
    bool start(unsigned part, Child& child, std::string& error);
    void pump(std::vector<Child>& children, const std::function<void(const std::string&)>& onReport);
    void addMessage(const std::string& line);

    std::string _program;
    std::vector<std::string> _arguments;
    unsigned _numJobs;
    int _worstStatus;
    std::vector<std::string> _messages;
};

} // namespace osgActorRender

#endif
