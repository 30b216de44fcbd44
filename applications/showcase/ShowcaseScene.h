/* osgactorshowcase: builds the showcase scene (data/showcase.osgt). */
#ifndef OSGACTORSHOWCASE_SHOWCASESCENE_H
#define OSGACTORSHOWCASE_SHOWCASESCENE_H 1

#include <osg/Group>

#include <string>

namespace osgActorShowcase {

/** Where the showcase's actors come from, as file names the scene's ProxyNodes load (relative to the scene file's
  * folder, or anywhere on osgDB's data path). */
struct ShowcaseSources
{
    std::string humanoid = "humanoid.actor";
    std::string insect = "insect.actor";
    /** The motion-capture dancer, a CMU Charleston (data/mocap, ASF + AMC) through osgdb_actor's mocap
      * pseudo-loader, which turns its Y up to Z up; empty: no dancer. */
    std::string dancer = "mocap/asfamc/charleston.asf.actor";
    /** From the file's units to metres: CMU skeletons are in units of 1/0.45 inch, 0.0254 / 0.45 m. */
    double dancerScale = 0.0254 / 0.45;
    /** Turn the dancer from Y up to Z up here (for a loader that does not). */
    bool dancerYUp = false;
};

/** The showcase: a checkered floor with obstacles under a sun; the humanoid walking a stored ellipse round the
  * dancer (PathWalker), the motion-capture dancer, and the six-legged insect wandering a stored figure of eight
  * between rocks with a tripod gait planted by leg IK (TripodGait). The actors are ProxyNodes, so the file stays
  * small and always shows the current actor files of data/; the rigs give them their controllers once loaded. */
osg::ref_ptr<osg::Group> makeShowcaseScene(const ShowcaseSources& sources);

} // namespace osgActorShowcase

#endif
