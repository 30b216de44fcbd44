/* The project's image regression helper: a rendered image against tests/render/references/<name>.png, through the
 * comparison osgActor::Offscreen offers its users. */
#ifndef OSGACTOR_TESTS_RENDER_IMAGECOMPARE_H
#define OSGACTOR_TESTS_RENDER_IMAGECOMPARE_H 1

#include <osgActor/Offscreen/ImageComparison>

#include <osg/Image>

#include <gtest/gtest.h>

#include <string>

namespace osgActor {
namespace test {

/** Compares an image with tests/render/references/<name>.png: it matches when at most maxFraction of its pixels
  * differ by more than threshold in a channel. On failure the actual image and the diff image are written to
  * <build>/tests/render/image-failures/<name>_actual.png and <name>_diff.png, and the message names them.
  *
  * With OSGACTOR_UPDATE_REFERENCES=1 in the environment the image is written as the new reference instead (and
  * the check passes): look at every image written that way before committing it. */
::testing::AssertionResult matchesReference(const osg::Image& actual, const std::string& name, int threshold = 24,
                                            double maxFraction = 0.003);

/** Whether two renders of one scene by two paths are the same bytes (no channel of any pixel differs), and the first
  * draws something other than the background over at least minShare of its pixels, so that the comparison could
  * fail. */
::testing::AssertionResult isTheSameBytesCovering(const osg::Image& actual, const osg::Image& expected,
                                                  const osg::Vec4& background, double minShare);

} // namespace test
} // namespace osgActor

#endif
