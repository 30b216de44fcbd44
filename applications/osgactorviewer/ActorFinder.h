/* osgactorviewer: finds the actors in a loaded scene. */
#ifndef OSGACTORVIEWER_ACTORFINDER_H
#define OSGACTORVIEWER_ACTORFINDER_H 1

#include <osgActor/ActorNode>

#include <osg/NodeVisitor>

#include <vector>

namespace osgActorViewer {

/** Every ActorNode below a node, in traversal order, each once (an actor shared by several parents is one actor).
  * Actors nested below another actor's skeleton nodes (a rider on a horse) are found too. */
std::vector<osg::ref_ptr<osgActor::ActorNode>> findActors(osg::Node& root);

} // namespace osgActorViewer

#endif
