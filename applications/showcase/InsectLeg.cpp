#include "InsectLeg.h"

#include <algorithm>
#include <cmath>

namespace osgActorShowcase {

bool InsectLeg::bind(const osgActor::ActorDefinition& definition, const std::string& legName, double tibiaReach)
{
    name = legName;
    side = legName.compare(0, 2, "r_") == 0 ? -1.0 : 1.0;
    const int coxa = definition.findJoint(legName + "_coxa");
    const int femur = definition.findJoint(legName + "_femur");
    const int tibia = definition.findJoint(legName + "_tibia");
    if (coxa < 0 || femur < 0 || tibia < 0) return false;
    const glm::dvec3& offset = definition.getOffsetTranslation(unsigned(coxa));
    coxaOffset.set(offset.x, offset.y, offset.z);
    coxaLength = std::abs(definition.getOffsetTranslation(unsigned(femur)).x);
    femurLength = std::abs(definition.getOffsetTranslation(unsigned(tibia)).x);
    tibiaLength = tibiaReach;
    coxaSwingDof = definition.getDofIndex(unsigned(coxa), osgActor::Dof::RZ);
    coxaTiltDof = definition.getDofIndex(unsigned(coxa), osgActor::Dof::RY);
    femurDof = definition.getDofIndex(unsigned(femur), osgActor::Dof::RY);
    tibiaDof = definition.getDofIndex(unsigned(tibia), osgActor::Dof::RY);
    return coxaSwingDof >= 0 && femurDof >= 0 && tibiaDof >= 0;
}

// Column-vector notation, as in the definition: Ry(angle) turns a left segment (L, 0, 0) to (L cos, 0, -L sin), so
// a positive femur or tibia angle bends a left leg downwards. The right legs are the left ones mirrored in the YZ
// plane, where every angle changes sign; the formulas are written for the left leg with angles times side.

osg::Vec3d InsectLeg::footPosition(double swing, double femur, double tibia) const
{
    // Left-leg angles: lift and knee measured so that positive bends downwards.
    const double f = side * femur;
    const double t = side * tibia;
    const double reach = coxaLength + femurLength * std::cos(f) + tibiaLength * std::cos(f + t);
    const double drop = femurLength * std::sin(f) + tibiaLength * std::sin(f + t);
    const double heading = side * swing; // the leg's direction in the thorax's XY plane, mirrored for the right
    return coxaOffset + osg::Vec3d(side * reach * std::cos(heading), reach * std::sin(heading), -drop);
}

void InsectLeg::solve(const osg::Vec3d& target, double& swing, double& femur, double& tibia) const
{
    const osg::Vec3d d = target - coxaOffset;
    // Swing: the leg's vertical plane through the target (mirrored in X for the right side).
    const double heading = std::atan2(d.y(), side * d.x());
    swing = side * heading;

    // Femur and tibia: two links from the femur joint to the target, in that plane (x outwards, h downwards).
    const double x = std::hypot(d.x(), d.y()) - coxaLength;
    const double h = -d.z();
    const double a = femurLength;
    const double b = tibiaLength;
    const double distance = std::clamp(std::hypot(x, h), std::abs(a - b) + 1e-9, a + b - 1e-9);
    const double cosKnee = (distance * distance - a * a - b * b) / (2.0 * a * b);
    const double knee = std::acos(std::clamp(cosKnee, -1.0, 1.0)); // >= 0: the knee bends downwards
    const double lift = std::atan2(h, x) - std::atan2(b * std::sin(knee), a + b * std::cos(knee));
    femur = side * lift;
    tibia = side * knee;
}

} // namespace osgActorShowcase
