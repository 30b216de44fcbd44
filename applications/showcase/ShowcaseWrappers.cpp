// osgDB wrappers of the showcase's drivers, so that scenes using them are written to and read from .osgt/.osgb.
// They live in the library itself: osgDB finds them by loading libosgActorShowcase.so for the osgActorShowcase::
// class names.
#include "PathWalker.h"
#include "TripodGait.h"

// Callbacks derive virtually from osg::Object: the serializers must cast down with dynamic_cast (as OSG's own
// callback wrappers do).
#undef OBJECT_CAST
#define OBJECT_CAST dynamic_cast

#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

namespace PathWalkerWrapper {
REGISTER_OBJECT_WRAPPER(osgActorShowcase_PathWalker, new osgActorShowcase::PathWalker, osgActorShowcase::PathWalker,
                        "osg::Object osg::Callback osg::NodeCallback osgActorShowcase::PathWalker")
{
    ADD_OBJECT_SERIALIZER(Path, osg::AnimationPath, NULL);
    ADD_DOUBLE_SERIALIZER(CycleDuration, 1.1);
}
} // namespace PathWalkerWrapper

namespace TripodGaitWrapper {
REGISTER_OBJECT_WRAPPER(osgActorShowcase_TripodGait, new osgActorShowcase::TripodGait, osgActorShowcase::TripodGait,
                        "osg::Object osg::Callback osg::NodeCallback osgActorShowcase::TripodGait")
{
    ADD_OBJECT_SERIALIZER(Path, osg::AnimationPath, NULL);
    ADD_DOUBLE_SERIALIZER(CycleDuration, 0.8);
    ADD_DOUBLE_SERIALIZER(StepHeight, 0.08);
    ADD_DOUBLE_SERIALIZER(TibiaReach, 0.57);
}
} // namespace TripodGaitWrapper
