/* osgActorShowcase: the paper's cockroach gait as a controller: a stored path for the body, leg IK for the feet. */
#ifndef OSGACTORSHOWCASE_TRIPODGAITCONTROLLER_H
#define OSGACTORSHOWCASE_TRIPODGAITCONTROLLER_H 1

#include "Export.h"

#include <osgActor/core/Trajectory>
#include <osgActor/core/ik/IkController>

#include <array>
#include <string>

namespace osgActorShowcase {

/** Walks a six-legged actor (data/insect.actor) along a stored path with a tripod gait, through the library's own
  * players and solvers. Each frame, in the actor's update, before forward kinematics:
  * 1. a TrajectoryPlayer (looping) moves the body: the path writes the pre-transform;
  * 2. each leg's foot goal is set in world space (IkGoalSpace::World) from the gait below;
  * 3. each leg's IkController solves the leg's IK chain (coxa, femur, tibia to the foot's tip) onto its goal.
  *
  * The gait: the legs move in two tripods (tripod A: l_front, r_middle, l_hind; tripod B: the other three, half a
  * cycle later), each foot on the ground for the first half of each of its steps (stance) and swinging for the
  * second. A foot on the ground stays where it was put down: at its rest position (the definition's default pose)
  * under the body as the path will place it half-way through that stance, so the body walks over planted feet; a
  * swinging foot moves to its next foothold on an arc of the step height. Time is the body player's play head, so
  * the feet and the path never drift apart.
  *
  * The chains, the path and the actor's definition are shared and immutable; the play head, the goals and the
  * solvers' scratch are this instance's, so a cloned actor walks on its own. The controller's weight and DOF
  * selection apply to the legs' IK as to any controller. */
class OSGACTORSHOWCASE_EXPORT TripodGaitController : public osgActor::Controller
{
public:
    /** The controller's name ("tripod gait"). */
    static const char* const kControllerName;
    static const unsigned kNumLegs = 6;
    /** The legs in gait order: tripod A (l_front, r_middle, l_hind), then tripod B (r_front, l_middle, r_hind). */
    static const char* const kLegNames[kNumLegs];
    /** The IK chain of a leg, "<leg>_leg": data/insect.actor has one per leg. */
    static std::string legChainName(unsigned leg) { return std::string(kLegNames[leg]) + "_leg"; }

    using LegChains = std::array<osgActor::IkChainPtr, kNumLegs>;
    /** A gait along path with the legs' chains in kLegNames order. */
    TripodGaitController(osgActor::TrajectoryPtr path, const LegChains& legChains);

    /** Seconds per gait cycle (each tripod steps once); values that are not positive are refused (false). */
    bool setCycleDuration(double seconds);
    double getCycleDuration() const { return _cycleDuration; }
    /** How high a swinging foot lifts (model units of the path's frame, >= 0); other values are refused. */
    bool setStepHeight(double height);
    double getStepHeight() const { return _stepHeight; }

    /** The body's player: its play head is the gait's time. */
    const osgActor::TrajectoryPlayer& getBodyPlayer() const { return _body; }
    /** A leg's IK controller (kLegNames order): its goal and last result. */
    const osgActor::IkController& getLegController(unsigned leg) const { return _legs[leg]; }

    /** True while the leg's foot is on the ground at a play time (seconds). */
    bool isInStance(unsigned leg, double playTime) const;
    /** Where the leg's foot is to be at a play time, in the actor's parent frame (the path's frame, model units);
      * only once the controller has run on the actor (the feet's rest positions come from its definition). */
    glm::dvec3 footTarget(unsigned leg, double playTime) const;

    void update(const osgActor::ControllerContext& context, osgActor::ControllerTarget& target) override;
    std::shared_ptr<osgActor::Controller> cloneController() const override;
    bool usesWorldSpace() const override { return true; }
    /** The body's path. */
    const osgActor::Trajectory* getFollowedPath() const override { return _body.getTrajectory().get(); }

private:
    /** Where the leg's foot stands during the stance of one of its steps (parent frame). */
    glm::dvec3 foothold(unsigned leg, double step) const;
    /** The rest feet (model space) of a definition, from its default pose; false if a chain does not fit it. */
    bool bindRestFeet(const osgActor::ActorDefinitionPtr& definition);

    osgActor::TrajectoryPlayer _body;
    std::array<osgActor::IkController, kNumLegs> _legs;
    double _cycleDuration = 0.8;
    double _stepHeight = 0.08;

    const osgActor::ActorDefinition* _restFeetDefinition = nullptr;
    std::array<glm::dvec3, kNumLegs> _restFeet{}; // the feet's tips in the default pose, model space
    osgActor::ActorTransforms _transforms;        // this frame's, for the post-transform of future body poses
    mutable std::size_t _pathCursor = 0;          // sampling cursor into the path, for the footholds
};

} // namespace osgActorShowcase

#endif
