/* osgactorrender: a private temporary folder for frames nobody asked to keep. */
#ifndef OSGACTORRENDER_SCRATCHFOLDER_H
#define OSGACTORRENDER_SCRATCHFOLDER_H 1

#include <string>

namespace osgActorRender {

/** A new folder under $TMPDIR (or /tmp), removed with everything in it when this object goes. Frames go there
  * when the sheets need them on disk (a --jobs parent reads back what its children rendered; the comparison sheet
  * reads back the frames that differ) and the user did not ask for them with -o. */
class ScratchFolder
{
public:
    ScratchFolder() = default;
    ~ScratchFolder();
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;

    /** Makes the folder; false, with the reason, if it cannot. */
    bool create(std::string& error);
    /** A pattern for the frames in it ("" before create()). */
    std::string getFramePattern() const { return _path.empty() ? "" : _path + "/frame_%08d.png"; }

private:
    std::string _path;
};

} // namespace osgActorRender

#endif
