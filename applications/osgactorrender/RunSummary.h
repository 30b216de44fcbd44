/* osgactorrender: what a run did, frame by frame, told at the end: lines, sheets, report and exit status. */
#ifndef OSGACTORRENDER_RUNSUMMARY_H
#define OSGACTORRENDER_RUNSUMMARY_H 1

#include "PartRenderer.h"
#include "ProgressBar.h"

#include <osgActor/Offscreen/ContactSheet>

#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace osgActorRender {

/** Collects the outcome of every frame of frames first..last, wherever it was rendered, with the progress bar;
  * then writes the contact sheet, the comparison sheet and the report and says what happened. */
class RunSummary : public FrameSink
{
public:
    RunSummary(const RenderOptions& options, unsigned first, unsigned last, bool showProgress);

    void frameDone(const FrameOutcome& outcome, const osg::Image* image) override;
    /** A step of the progress bar that is no frame's outcome (the renders of --check-determinism). */
    void step() { _progress.step(); }
    /** Ends the progress bar's line (before any other message). */
    void endProgress() { _progress.finish(); }

    /** Writes the sheets and the report and prints a line per differing frame and the summary to out. Frames
      * handed over without an image are read back from renderFiles (a pattern). The exit status: 1 if a frame
      * differs from its reference, 0 otherwise; 2, with the reason, if a file cannot be read or written. */
    int finish(const std::string& renderFiles, std::ostream& out, std::string& error);

    unsigned getNumFramesDone() const { return unsigned(_outcomes.size()); }

private:
    bool writeContactSheet(const std::string& renderFiles, std::string& error);
    bool writeCompareSheet(const std::vector<const FrameOutcome*>& differing, const std::string& renderFiles,
                           std::string& error);
    bool writeReport(std::string& error) const;
    void printDifferingFrame(const FrameOutcome& outcome, std::ostream& out) const;

    const RenderOptions& _options;
    unsigned _first;
    unsigned _last;
    ProgressBar _progress;
    std::vector<FrameOutcome> _outcomes;
    std::unique_ptr<osgActor::ContactSheet> _contactSheet;
    /** Which tiles of the contact sheet were filled from an image handed over. */
    std::vector<bool> _tileFilled;
};

} // namespace osgActorRender

#endif
