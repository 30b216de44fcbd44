/* Shared by the applications: loads the files named on a command line into one scene, with clear errors. */
#ifndef OSGACTORAPPS_SCENELOADER_H
#define OSGACTORAPPS_SCENELOADER_H 1

#include <osg/Node>

#include <string>
#include <vector>

namespace osgActorApps {

/** Reads one file through osgDB (any format with a plugin: .actor, .osgt, pseudo-loaders such as walk.bvh.actor);
  * null, with a message naming the file and what went wrong, when it cannot be read. */
osg::ref_ptr<osg::Node> loadSceneFile(const std::string& file, std::string& error);

/** Reads every file, all or nothing: one node when there is one file, a group of them otherwise. */
osg::ref_ptr<osg::Node> loadSceneFiles(const std::vector<std::string>& files, std::string& error);

} // namespace osgActorApps

#endif
