#include "TripodGait.h"

#include <cmath>

namespace osgActorShowcase {

const char* const TripodGait::kLegNames[6] = {"l_front", "r_middle", "l_hind", "r_front", "l_middle", "r_hind"};

TripodGait::TripodGait() : _cycleDuration(0.8), _stepHeight(0.08), _tibiaReach(0.57) {}

TripodGait::TripodGait(const TripodGait& gait, const osg::CopyOp& copyop)
    : osg::Object(gait, copyop), osg::Callback(gait, copyop), ActorDriver(gait, copyop), _path(gait._path), _cycleDuration(gait._cycleDuration),
      _stepHeight(gait._stepHeight), _tibiaReach(gait._tibiaReach)
{
}

osg::Matrixd TripodGait::bodyMatrix(double time) const
{
    osg::Matrixd matrix;
    if (_path.valid() && !_path->empty()) _path->getMatrix(time, matrix);
    return matrix;
}

osg::Vec3d TripodGait::footTarget(unsigned legIndex, const osg::Vec3d& restFoot, double time) const
{
    // Tripod B runs half a cycle behind tripod A. u counts this leg's steps; in each, half stance then half swing.
    const double lag = legIndex < 3 ? 0.0 : 0.5;
    const double u = time / _cycleDuration + lag;
    const double step = std::floor(u);
    const double within = u - step;
    // The foothold of step k: the rest position under the body a quarter cycle into that step (mid-stance).
    const auto foothold = [&](double k) { return restFoot * bodyMatrix((k + 0.25 - lag) * _cycleDuration); };

    if (within < 0.5) return foothold(step);
    const double s = (within - 0.5) * 2.0;           // 0..1 through the swing
    const double eased = s * s * (3.0 - 2.0 * s);    // leaves and lands softly
    osg::Vec3d foot = foothold(step) * (1.0 - eased) + foothold(step + 1.0) * eased;
    foot.z() += _stepHeight * std::sin(osg::PI * s);
    return foot;
}

void TripodGait::drive(osgActor::ActorNode& actor, double time)
{
    if (!actor.getDefinition() || _cycleDuration <= 0.0) return;
    const osgActor::ActorDefinition& definition = *actor.getDefinition();
    const int thorax = definition.findJoint("thorax");
    if (thorax < 0) return;

    const osg::Matrixd body = bodyMatrix(time);
    actor.setPreTranslation(body.getTrans());
    actor.setPreRotation(body.getRotate());

    // From the path's frame into the thorax joint's frame (OSG's row-vector order: the thorax's model matrix, then
    // the body's pre-transform).
    const osg::Matrixd thoraxModel = actor.getJointModelMatrix(unsigned(thorax));
    const osg::Matrixd pathToThorax = osg::Matrixd::inverse(thoraxModel * body);

    for (unsigned i = 0; i < 6; ++i)
    {
        InsectLeg leg;
        if (!leg.bind(definition, kLegNames[i], _tibiaReach)) continue;
        // The rest foot: the defaults' pose, in the actor's frame.
        const osg::Vec3d restFoot = leg.footPosition(definition.getDofDefault(unsigned(leg.coxaSwingDof)),
                                                     definition.getDofDefault(unsigned(leg.femurDof)),
                                                     definition.getDofDefault(unsigned(leg.tibiaDof))) *
                                    thoraxModel;
        double swing = 0.0, femur = 0.0, tibia = 0.0;
        leg.solve(footTarget(i, restFoot, time) * pathToThorax, swing, femur, tibia);
        actor.setDof(unsigned(leg.coxaSwingDof), swing);
        if (leg.coxaTiltDof >= 0) actor.setDof(unsigned(leg.coxaTiltDof), 0.0);
        actor.setDof(unsigned(leg.femurDof), femur);
        actor.setDof(unsigned(leg.tibiaDof), tibia);
    }
}

} // namespace osgActorShowcase
