/* osgactorrender: output file names from a printf-like pattern such as out/frame_%04d.png. */
#ifndef OSGACTORRENDER_OUTPUTPATTERN_H
#define OSGACTORRENDER_OUTPUTPATTERN_H 1

#include <string>

namespace osgActorRender {

/** A file-name pattern with at most one frame-number field: %d, or %0Nd / %Nd (N up to 9); %% is a percent sign.
  * Nothing else is formatted, so a pattern can never read arguments that are not there. */
class OutputPattern
{
public:
    /** False, with the reason in error, if the pattern is empty or holds any other % conversion. */
    bool parse(const std::string& pattern, std::string& error);

    /** A pattern parse() accepted before (an empty one formats every frame as ""). */
    static OutputPattern fromChecked(const std::string& pattern);

    /** True if the pattern has a frame-number field (needed to write more than one frame). */
    bool hasFrameField() const { return _hasField; }
    /** The file name of a frame. */
    std::string format(unsigned frame) const;

private:
    std::string _prefix;
    std::string _suffix;
    bool _hasField = false;
    bool _zeroPad = false;
    int _width = 0;
};

} // namespace osgActorRender

#endif
