// osgDB wrappers of the showcase's rigs and of its shadow map, so that scenes using them are written to and read
// from .osgt/.osgb. They live in the library itself: osgDB finds them by loading libosgActorShowcase.so for the
// osgActorShowcase:: class names.
#include "LightNumberShadowMap.h"
#include "PathWalker.h"
#include "TripodGait.h"

// Callbacks derive virtually from osg::Object: the serializers must cast down with dynamic_cast (as OSG's own
// callback wrappers do).
#undef OBJECT_CAST
#define OBJECT_CAST dynamic_cast

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

namespace {

// The stored path of a rig (an osgActor::Trajectory), written in full:
//     Path "name" <number of keys> {
//         time x y z heading      (seconds, model units of the actor's parent frame, radians)
//         ...
//     }
// On reading, the keys are validated as TrajectoryBuilder does; a bad path fails the read with its reason.

const unsigned int kMaxPathKeys = 10000000; // a sanity bound against a corrupt count

template <class Rig>
bool checkPath(const Rig& rig)
{
    return rig.getPath() != nullptr;
}

template <class Rig>
bool readPath(osgDB::InputStream& is, Rig& rig)
{
    std::string name;
    is.readWrappedString(name);
    unsigned int count = 0;
    is >> count >> is.BEGIN_BRACKET;
    if (is.getException()) return false;
    if (count > kMaxPathKeys)
    {
        is.throwException("osgActorShowcase: path '" + name + "' claims " + std::to_string(count) + " keys");
        return false;
    }
    std::vector<osgActor::TrajectoryKey> keys(count);
    for (osgActor::TrajectoryKey& key : keys)
        is >> key.time >> key.position.x >> key.position.y >> key.position.z >> key.heading;
    is >> is.END_BRACKET;
    if (is.getException()) return false;
    const osgActor::TrajectoryBuildResult built = osgActor::TrajectoryBuilder::build(name, std::move(keys));
    if (!built)
    {
        is.throwException("osgActorShowcase: " + built.error);
        return false;
    }
    rig.setPath(built.trajectory);
    return true;
}

template <class Rig>
bool writePath(osgDB::OutputStream& os, const Rig& rig)
{
    const osgActor::Trajectory& path = *rig.getPath();
    os.writeWrappedString(path.getName());
    os << static_cast<unsigned int>(path.getKeys().size()) << os.BEGIN_BRACKET << std::endl;
    for (const osgActor::TrajectoryKey& key : path.getKeys())
        os << key.time << key.position.x << key.position.y << key.position.z << key.heading << std::endl;
    os << os.END_BRACKET << std::endl;
    return true;
}

} // namespace

namespace PathWalkerWrapper {
REGISTER_OBJECT_WRAPPER(osgActorShowcase_PathWalker, new osgActorShowcase::PathWalker, osgActorShowcase::PathWalker,
                        "osg::Object osg::Callback osg::NodeCallback osgActorShowcase::PathWalker")
{
    ADD_USER_SERIALIZER(Path);
    ADD_DOUBLE_SERIALIZER(CycleDuration, 1.1);
}
} // namespace PathWalkerWrapper

namespace TripodGaitWrapper {
REGISTER_OBJECT_WRAPPER(osgActorShowcase_TripodGait, new osgActorShowcase::TripodGait, osgActorShowcase::TripodGait,
                        "osg::Object osg::Callback osg::NodeCallback osgActorShowcase::TripodGait")
{
    ADD_USER_SERIALIZER(Path);
    ADD_DOUBLE_SERIALIZER(CycleDuration, 0.8);
    ADD_DOUBLE_SERIALIZER(StepHeight, 0.08);
}
} // namespace TripodGaitWrapper

namespace LightNumberShadowMapWrapper {
// ShadowMap's own properties (texture unit and size, polygon offset, ambient bias) come from osgShadow's wrapper.
REGISTER_OBJECT_WRAPPER(osgActorShowcase_LightNumberShadowMap, new osgActorShowcase::LightNumberShadowMap,
                        osgActorShowcase::LightNumberShadowMap,
                        "osg::Object osgShadow::ShadowTechnique osgShadow::ShadowMap "
                        "osgActorShowcase::LightNumberShadowMap")
{
    ADD_INT_SERIALIZER(LightNumber, 0);
}
} // namespace LightNumberShadowMapWrapper
