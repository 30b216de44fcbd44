#include "SceneLoader.h"

#include <osg/Group>
#include <osgDB/Registry>

namespace osgActorApps {

osg::ref_ptr<osg::Node> loadSceneFile(const std::string& file, std::string& error)
{
    osgDB::Registry* registry = osgDB::Registry::instance();
    osgDB::ReaderWriter::ReadResult result = registry->readNode(file, registry->getOptions());
    if (result.validNode()) return result.getNode();

    error = "cannot read \"" + file + "\": ";
    if (!result.message().empty()) error += result.message();
    else if (result.status() == osgDB::ReaderWriter::ReadResult::FILE_NOT_FOUND) error += "file not found";
    else if (result.status() == osgDB::ReaderWriter::ReadResult::FILE_NOT_HANDLED)
        error += "no osgDB plugin reads this file (unknown extension, or not in a format the plugin accepts)";
    else if (result.status() == osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE)
        error += "the file is damaged or not in the format its extension says";
    else error += "it holds no scene";
    return nullptr;
}

osg::ref_ptr<osg::Node> loadSceneFiles(const std::vector<std::string>& files, std::string& error)
{
    if (files.empty())
    {
        error = "no file to load";
        return nullptr;
    }
    if (files.size() == 1) return loadSceneFile(files.front(), error);

    osg::ref_ptr<osg::Group> group = new osg::Group;
    for (const std::string& file : files)
    {
        osg::ref_ptr<osg::Node> node = loadSceneFile(file, error);
        if (!node) return nullptr;
        group->addChild(node.get());
    }
    return group;
}

} // namespace osgActorApps
