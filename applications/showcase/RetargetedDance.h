/* osgActorShowcase: an actor dancing a motion of another skeleton, retargeted onto it when the scene loads. */
#ifndef OSGACTORSHOWCASE_RETARGETEDDANCE_H
#define OSGACTORSHOWCASE_RETARGETEDDANCE_H 1

#include "ControllerRig.h"

#include <osgActor/core/retarget/RetargetClip>

#include <string>

namespace osgActorShowcase {

/** Makes the actors of its group dance a motion-capture clip of another skeleton (an AMC motion and its ASF
  * skeleton; the showcase's: CMU's Charleston, mocap/asfamc/charleston.asf and charleston1.amc), retargeted onto each
  * actor when it first appears (osgActor::retargetClipOntoActor(), the joint maps guessed, with the IK pass:
  * retargetOptions()). The files are found as the scene's ProxyNodes find theirs: in the database path (the folder of
  * the scene file it was read from) first, then on osgDB's data path. The actor's
  * own clip players give way to one that loops the retargeted clip (named kControllerName). A motion that cannot be
  * found, read or retargeted is reported once with OSG_WARN naming the file, and the actor is left as it was. */
class OSGACTORSHOWCASE_EXPORT RetargetedDance : public ControllerRig
{
public:
    RetargetedDance() = default;
    RetargetedDance(const RetargetedDance& dance, const osg::CopyOp& copyop = osg::CopyOp::SHALLOW_COPY);

    META_Object(osgActorShowcase, RetargetedDance);

    /** The ASF skeleton the motion is read against, as osgDB's data path finds it. */
    void setSkeletonFile(const std::string& file) { _skeletonFile = file; }
    const std::string& getSkeletonFile() const { return _skeletonFile; }
    /** The motion (an AMC file), as osgDB's data path finds it. */
    void setMotionFile(const std::string& file) { _motionFile = file; }
    const std::string& getMotionFile() const { return _motionFile; }

    /** The folder the files are looked for in first (as osg::ProxyNode's): set from the reading options when the rig
      * is read from a scene file (its folder), not written. */
    void setDatabasePath(const std::string& path) { _databasePath = path; }
    const std::string& getDatabasePath() const { return _databasePath; }

    /** The name of the player of the retargeted clip, which marks a rigged actor. */
    static const char* const kControllerName;
    /** How the motion is retargeted: the clip's name, and the IK pass that keeps the feet planted. */
    static osgActor::RetargetClipOptions retargetOptions();

    const char* getRigControllerName() const override { return kControllerName; }
    /** Reads the motion, retargets it onto the actor (its clip library gets the clip) and plays it in a loop in place
      * of the actor's own clip players; false, with an OSG_WARN naming the file, and the actor unchanged, when the
      * files cannot be found or read or the skeletons have no joints in common. */
    bool rig(osgActor::ActorNode& actor) const override;

protected:
    ~RetargetedDance() override = default;

    std::string _skeletonFile;
    std::string _motionFile;
    std::string _databasePath;
};

} // namespace osgActorShowcase

#endif
