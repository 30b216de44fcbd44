/* osgactorconv --retarget: a motion the converter reads, retargeted onto the actor of a .actor file (issue 27). */
#ifndef OSGACTORCONV_RETARGETCONVERSION_H
#define OSGACTORCONV_RETARGETCONVERSION_H 1

#include <osgActor/mocap/MocapImport>

#include <string>

/** What --retarget needs besides the motion. */
struct RetargetConversion
{
    /** The target actor's .actor file (its unnamed jointmap section maps its joints, else they are guessed). */
    std::string targetFile;
    /** A joint map file for the motion's skeleton (docs/retargeting.md); empty: guessed. */
    std::string mapFile;
    /** Where the target's .actor file goes with the new clip: the target file itself when empty. */
    std::string outputFile;
    /** The IK pass: feet planted during the source's contacts, hands and feet where the source puts them. */
    bool ik = true;
};

/** Retargets motion (read Z-up, as an actor) onto the target's actor, adds it to the target's clips under the motion's
  * name (replacing a clip of that name; playing in a loop when no other clip or player plays), writes the target's
  * file, and prints what the retargeting noticed and measured. Returns the exit status: 0, or 1 with a message on
  * stderr (a target or map that cannot be read, names file and line). */
int retargetIntoActorFile(const RetargetConversion& conversion, const osgActor::MocapImport& motion);

#endif
