// osgDB wrappers of the showcase's rigs and of its shadow map, so that scenes using them are written to and read
// from .osgt/.osgb. They live in the library itself: osgDB finds them by loading libosgActorShowcase.so for the
// osgActorShowcase:: class names.
#include "LightNumberShadowMap.h"
#include "PathWalker.h"
#include "RetargetedDance.h"
#include "TripodGait.h"

// Callbacks derive virtually from osg::Object: the serializers must cast down with dynamic_cast (as OSG's own
// callback wrappers do).
#undef OBJECT_CAST
#define OBJECT_CAST dynamic_cast

#include <osgActor/StreamNumbers>

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
    const std::string what = "path '" + name + "'";
    for (osgActor::TrajectoryKey& key : keys)
        for (double* value : {&key.time, &key.position.x, &key.position.y, &key.position.z, &key.heading})
            if (!osgActor::readStreamNumber(is, *value, what)) return false;
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
    {
        for (const double value : {key.time, key.position.x, key.position.y, key.position.z, key.heading})
            osgActor::writeStreamNumber(os, value);
        os << std::endl;
    }
    os << os.END_BRACKET << std::endl;
    return true;
}

// A rig's double property NAME (setNAME/getNAME), written exactly where OSG's ADD_DOUBLE_SERIALIZER would write the
// stream's precision in .osgt; the same "NAME value" field, so files written before read as they did.
#define OSGACTORSHOWCASE_EXACT_DOUBLE(NAME)                                                                        \
    template <class Rig>                                                                                           \
    bool check##NAME(const Rig&)                                                                                   \
    {                                                                                                              \
        return true;                                                                                               \
    }                                                                                                              \
    template <class Rig>                                                                                           \
    bool read##NAME(osgDB::InputStream& is, Rig& rig)                                                              \
    {                                                                                                              \
        double value = 0.0;                                                                                        \
        if (!osgActor::readStreamNumber(is, value, #NAME)) return false;                                           \
        rig.set##NAME(value);                                                                                      \
        return true;                                                                                               \
    }                                                                                                              \
    template <class Rig>                                                                                           \
    bool write##NAME(osgDB::OutputStream& os, const Rig& rig)                                                      \
    {                                                                                                              \
        osgActor::writeStreamNumber(os, rig.get##NAME());                                                          \
        os << std::endl;                                                                                           \
        return true;                                                                                               \
    }

OSGACTORSHOWCASE_EXACT_DOUBLE(CycleDuration)
OSGACTORSHOWCASE_EXACT_DOUBLE(StepHeight)

/** Gives a RetargetedDance read from a file the folder it was read from (the first of the reading options' database
  * paths, as osgDB's reader of .osgt/.osgb puts it there), where it looks for its motion first, as the scene's
  * ProxyNodes do. */
struct TakeDatabasePath : public osgDB::FinishedObjectReadCallback
{
    void objectRead(osgDB::InputStream& is, osg::Object& object) override
    {
        auto* dance = dynamic_cast<osgActorShowcase::RetargetedDance*>(&object);
        const osgDB::Options* options = is.getOptions();
        if (dance && options && !options->getDatabasePathList().empty())
            dance->setDatabasePath(options->getDatabasePathList().front());
    }
};

} // namespace

namespace PathWalkerWrapper {
REGISTER_OBJECT_WRAPPER(osgActorShowcase_PathWalker, new osgActorShowcase::PathWalker, osgActorShowcase::PathWalker,
                        "osg::Object osg::Callback osg::NodeCallback osgActorShowcase::PathWalker")
{
    ADD_USER_SERIALIZER(Path);
    ADD_USER_SERIALIZER(CycleDuration);
}
} // namespace PathWalkerWrapper

namespace RetargetedDanceWrapper {
// The files by the names the scene gives them (found on osgDB's data path when the actor is rigged).
REGISTER_OBJECT_WRAPPER(osgActorShowcase_RetargetedDance, new osgActorShowcase::RetargetedDance,
                        osgActorShowcase::RetargetedDance,
                        "osg::Object osg::Callback osg::NodeCallback osgActorShowcase::RetargetedDance")
{
    ADD_STRING_SERIALIZER(SkeletonFile, "");
    ADD_STRING_SERIALIZER(MotionFile, "");
    wrapper->addFinishedObjectReadCallback(new TakeDatabasePath);
}
} // namespace RetargetedDanceWrapper

namespace TripodGaitWrapper {
REGISTER_OBJECT_WRAPPER(osgActorShowcase_TripodGait, new osgActorShowcase::TripodGait, osgActorShowcase::TripodGait,
                        "osg::Object osg::Callback osg::NodeCallback osgActorShowcase::TripodGait")
{
    ADD_USER_SERIALIZER(Path);
    ADD_USER_SERIALIZER(CycleDuration);
    ADD_USER_SERIALIZER(StepHeight);
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
