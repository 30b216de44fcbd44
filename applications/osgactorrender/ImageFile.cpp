#include "ImageFile.h"

#include <osgDB/FileUtils>
#include <osgDB/WriteFile>

namespace osgActorRender {

bool writeImage(const osg::Image& image, const std::string& file, std::string& error)
{
    osgDB::makeDirectoryForFile(file);
    if (osgDB::writeImageFile(image, file)) return true;
    error = "cannot write \"" + file + "\" (is the folder writable, and the extension one osgDB writes, e.g. .png?)";
    return false;
}

} // namespace osgActorRender
