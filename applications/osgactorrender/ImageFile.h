/* osgactorrender: writing images, with a message that says what to check. */
#ifndef OSGACTORRENDER_IMAGEFILE_H
#define OSGACTORRENDER_IMAGEFILE_H 1

#include <osg/Image>

#include <string>

namespace osgActorRender {

/** Writes the image through osgDB, making its folder first; false, with a message naming the file, otherwise. */
bool writeImage(const osg::Image& image, const std::string& file, std::string& error);

} // namespace osgActorRender

#endif
