/* osgactorrender: a one-line progress bar for long batches, on stderr. */
#ifndef OSGACTORRENDER_PROGRESSBAR_H
#define OSGACTORRENDER_PROGRESSBAR_H 1

#include <chrono>
#include <cstdio>

namespace osgActorRender {

/** Redraws "[#####.....]  12/48 frames  3.1 ms/frame" in place with a carriage return. Draws nothing unless enabled,
  * so that logs and pipes stay clean: enable it when the stream is a terminal or when the user asks. */
class ProgressBar
{
public:
    ProgressBar(unsigned total, bool enabled, std::FILE* stream = stderr);
    /** True if stream is a terminal. */
    static bool isTerminal(std::FILE* stream);

    /** One more item done. */
    void step();
    /** Ends the line (once everything is done, or early on an error). */
    void finish();

private:
    void draw() const;

    unsigned _total;
    unsigned _done;
    bool _enabled;
    bool _finished;
    std::FILE* _stream;
    std::chrono::steady_clock::time_point _start;
};

} // namespace osgActorRender

#endif
