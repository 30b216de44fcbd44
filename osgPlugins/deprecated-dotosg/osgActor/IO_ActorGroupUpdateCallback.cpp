/* osgActor::ActorGroupUpdateCallback in the .osg format. It has no fields. */
#include <osgActor/ActorGroup>

#include <osgDB/Input>
#include <osgDB/Output>
#include <osgDB/Registry>

namespace {

bool readActorGroupUpdateCallback(osg::Object&, osgDB::Input&) { return false; }
bool writeActorGroupUpdateCallback(const osg::Object&, osgDB::Output&) { return true; }

} // namespace

REGISTER_DOTOSGWRAPPER(osgActor_ActorGroupUpdateCallback)
(new osgActor::ActorGroupUpdateCallback, "osgActor::ActorGroupUpdateCallback",
 "Object NodeCallback osgActor::ActorGroupUpdateCallback", &readActorGroupUpdateCallback,
 &writeActorGroupUpdateCallback, osgDB::DotOsgWrapper::READ_AND_WRITE);
