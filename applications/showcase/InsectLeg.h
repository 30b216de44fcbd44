/* osgActorShowcase: one leg of the six-legged insect (data/insect.actor), and its inverse kinematics. */
#ifndef OSGACTORSHOWCASE_INSECTLEG_H
#define OSGACTORSHOWCASE_INSECTLEG_H 1

#include "Export.h"

#include <osgActor/core/ActorDefinition>

#include <osg/Vec3d>

#include <string>

namespace osgActorShowcase {

/** A leg: coxa (rz swings it forwards and backwards, ry tilt held at 0), femur (ry lifts it) and tibia (ry bends
  * the knee), each segment along the joint's local X, +X on the left side and -X on the right. Lengths in model
  * units, read from the actor's definition; the tibia's reach (to the foot's tip) is a property of its geometry. */
struct OSGACTORSHOWCASE_EXPORT InsectLeg
{
    std::string name;       // "l_front", ..., "r_hind"
    double side = 1.0;      // +1 left, -1 right
    osg::Vec3d coxaOffset;  // the coxa joint in the thorax joint's frame
    double coxaLength = 0.0;
    double femurLength = 0.0;
    double tibiaLength = 0.0; // to the tip of the foot
    int coxaSwingDof = -1;    // <name>_coxa.rz
    int coxaTiltDof = -1;     // <name>_coxa.ry
    int femurDof = -1;        // <name>_femur.ry
    int tibiaDof = -1;        // <name>_tibia.ry

    /** Reads the leg's joints from a definition; false if one of its joints or DOFs is missing. */
    bool bind(const osgActor::ActorDefinition& definition, const std::string& legName, double tibiaReach);

    /** Where the foot's tip is, in the thorax joint's frame, for the given swing, femur and tibia angles (radians). */
    osg::Vec3d footPosition(double swing, double femur, double tibia) const;

    /** The angles that put the foot's tip on a target in the thorax joint's frame (the knee bending downwards).
      * A target beyond reach is approached along the line to it (the leg stretched). */
    void solve(const osg::Vec3d& target, double& swing, double& femur, double& tibia) const;
};

} // namespace osgActorShowcase

#endif
