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
    /** The actor walking round the dancer: Cesium Man (data/models/CesiumMan, glTF, skinned on the GPU) through
      * osgdb_actor's rigged-model pseudo-loader, playing his walk clip. An actor without a clip of its own (such as
      * humanoid.actor) walks the procedural cycle instead (PathWalker). */
    std::string walker = "models/CesiumMan/CesiumMan.gltf.actor";
    /** The walker's speed along its path (m/s): the one at which Cesium Man's planted foot slides least over the
      * floor as his clip plays (the tests measure it). */
    double walkerSpeed = 1.0;
    /** Seconds per cycle of the procedural walk, for a walker without a clip of its own (1.1 m/s suits 1.1 s). */
    double walkerCycleDuration = 1.1;
    std::string insect = "insect.actor";
    /** The motion-capture dancer, a CMU Charleston (data/mocap, ASF + AMC) through osgdb_actor's mocap
      * pseudo-loader, which turns its Y up to Z up; empty: no dancer. */
    std::string dancer = "mocap/asfamc/charleston.asf.actor";
    /** From the file's units to metres: CMU skeletons are in units of 1/0.45 inch, 0.0254 / 0.45 m. */
    double dancerScale = 0.0254 / 0.45;
    /** Turn the dancer from Y up to Z up here (for a loader that does not). */
    bool dancerYUp = false;
    /** The motion a second walker model (Cesium Man) dances beside the dancer, retargeted onto him at load
      * (RetargetedDance): an ASF skeleton and its AMC motion, the dancer's own; an empty motion (or no dancer): no
      * second dancer. */
    std::string danceSkeleton = "mocap/asfamc/charleston.asf";
    std::string danceMotion = "mocap/asfamc/charleston1.amc";
};

/** The node masks of the showcase's shadows (osgShadow::ShadowedScene's traversal masks): the floor has the
  * receiving bit only; every other node has all bits, so it casts and receives. */
const unsigned kReceivesShadowMask = 0x1;
const unsigned kCastsShadowMask = 0x2;

/** The showcase: a checkered floor with obstacles under a sun that casts shadows (an osgShadow::ShadowedScene with
  * a ShadowMap, the root); Cesium Man walking a stored ellipse round the dancer (PathWalker), the motion-capture
  * dancer, a second Cesium Man beside it dancing its motion retargeted onto him at load (RetargetedDance), and the
  * six-legged insect wandering a stored figure of eight between rocks with a tripod gait planted by
  * leg IK (TripodGait). The actors are ProxyNodes, so the file stays small and always shows the current actor and
  * model files of data/; the rigs give them their controllers once loaded. */
osg::ref_ptr<osg::Group> makeShowcaseScene(const ShowcaseSources& sources);

} // namespace osgActorShowcase

#endif
