/* osgActor::ActorUpdateCallback in the .osg format. It has no fields. */
#include <osgActor/ActorUpdateCallback>

#include <osgDB/Input>
#include <osgDB/Output>
#include <osgDB/Registry>

namespace {

bool readActorUpdateCallback(osg::Object&, osgDB::Input&) { return false; }
bool writeActorUpdateCallback(const osg::Object&, osgDB::Output&) { return true; }

} // namespace

REGISTER_DOTOSGWRAPPER(osgActor_ActorUpdateCallback)
(new osgActor::ActorUpdateCallback, "osgActor::ActorUpdateCallback",
 "Object NodeCallback osgActor::ActorUpdateCallback",
 &readActorUpdateCallback, &writeActorUpdateCallback, osgDB::DotOsgWrapper::READ_AND_WRITE);
