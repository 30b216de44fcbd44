// The renderer's helpers that need no GL: output file patterns, camera framing, contact sheets.
#include "CameraView.h"
#include "OutputPattern.h"

#include <osgActor/Offscreen/ContactSheet>

#include <osg/Geode>
#include <osg/MatrixTransform>
#include <osg/ShapeDrawable>

#include <gtest/gtest.h>

#include <cmath>

using namespace osgActorRender;
using namespace osgActorApps;
using osgActor::ContactSheet;

TEST(OutputPattern, RefusesEmptyAndUnsafePatterns)
{
    OutputPattern pattern;
    std::string error;
    EXPECT_FALSE(pattern.parse("", error));
    EXPECT_FALSE(pattern.parse("frame_%s.png", error));
    EXPECT_NE(error.find("frame_%s.png"), std::string::npos);
    EXPECT_FALSE(pattern.parse("%d_%d.png", error));      // two fields
    EXPECT_FALSE(pattern.parse("frame_%012d.png", error)); // width beyond 9
    EXPECT_FALSE(pattern.parse("frame_%", error));         // dangling
    EXPECT_FALSE(pattern.parse("frame_%n.png", error));
}

TEST(OutputPattern, FormatsTheFrameNumber)
{
    OutputPattern pattern;
    std::string error;
    ASSERT_TRUE(pattern.parse("out/frame_%04d.png", error)) << error;
    EXPECT_TRUE(pattern.hasFrameField());
    EXPECT_EQ(pattern.format(7), "out/frame_0007.png");
    EXPECT_EQ(pattern.format(123456), "out/frame_123456.png");
    ASSERT_TRUE(pattern.parse("f%d%%.png", error)) << error;
    EXPECT_EQ(pattern.format(42), "f42%.png");
    ASSERT_TRUE(pattern.parse("f%3d.png", error)) << error;
    EXPECT_EQ(pattern.format(5), "f  5.png");
    ASSERT_TRUE(pattern.parse("single.png", error)) << error;
    EXPECT_FALSE(pattern.hasFrameField());
    EXPECT_EQ(pattern.format(9), "single.png");
}

TEST(CameraView, InvalidBoundGivesTheDefaultView)
{
    const CameraView view = frameBoundingSphere(osg::BoundingSphere(), 30.0, 4.0 / 3.0);
    EXPECT_EQ(view.center, CameraView().center);
    EXPECT_EQ(view.eye, CameraView().eye);
}

TEST(CameraView, FramedSphereFitsTheNarrowerFieldOfView)
{
    const osg::BoundingSphere bound(osg::Vec3(1, 2, 3), 2.0f);
    for (double aspect : {0.5, 1.0, 2.0})
    {
        const CameraView view = frameBoundingSphere(bound, 30.0, aspect);
        EXPECT_EQ(view.center, osg::Vec3d(1, 2, 3));
        const double distance = (view.eye - view.center).length();
        const double halfFovy = osg::DegreesToRadians(15.0);
        const double halfFovx = std::atan(std::tan(halfFovy) * aspect);
        // The sphere touches the narrower half angle exactly.
        EXPECT_NEAR(std::asin(2.0 / distance), std::min(halfFovy, halfFovx), 1e-6) << "aspect " << aspect;
        EXPECT_GT(view.eye.z(), view.center.z()); // from above
        EXPECT_LT(view.eye.y(), view.center.y()); // from the front (-Y)
    }
}

TEST(CameraView, ShownBoundHoldsTheDrawablesAsPlacedNotTheNodesBounds)
{
    // A unit cube (half size 1) 5 along X, under a node whose own bound is a far larger ball.
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(new osg::ShapeDrawable(new osg::Box(osg::Vec3(), 2.0f)));
    osg::ref_ptr<osg::MatrixTransform> placed = new osg::MatrixTransform(osg::Matrixd::translate(5, 0, 0));
    placed->addChild(geode.get());
    placed->setInitialBound(osg::BoundingSphere(osg::Vec3(), 100.0f));
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    scene->addChild(placed.get());
    ASSERT_GT(scene->getBound().radius(), 90.0f);
    const osg::BoundingSphere shown = shownBound(*scene);
    EXPECT_NEAR((osg::Vec3d(shown.center()) - osg::Vec3d(5, 0, 0)).length(), 0.0, 1e-6);
    EXPECT_NEAR(shown.radius(), std::sqrt(3.0), 1e-6); // half the cube's diagonal
    // Nothing drawn: the scene's own bound.
    osg::ref_ptr<osg::Group> empty = new osg::Group;
    empty->setInitialBound(osg::BoundingSphere(osg::Vec3(1, 2, 3), 4.0f));
    EXPECT_EQ(shownBound(*empty).center(), osg::Vec3(1, 2, 3));
    EXPECT_FLOAT_EQ(shownBound(*empty).radius(), 4.0f);
}

namespace {

osg::ref_ptr<osg::Image> solidFrame(int width, int height, unsigned char value)
{
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(width, height, 1, GL_RGB, GL_UNSIGNED_BYTE);
    std::fill(image->data(), image->data() + width * height * 3, value);
    return image;
}

} // namespace

TEST(ContactSheet, RefusesFramesThatDoNotFit)
{
    ContactSheet sheet(2, 0, 40, 30, 20, osg::Vec4(0, 0, 0, 1));
    EXPECT_FALSE(sheet.addFrame(2, *solidFrame(40, 30, 255)));  // no tile 2
    EXPECT_FALSE(sheet.addFrame(0, *solidFrame(41, 30, 255)));  // wrong size
    osg::ref_ptr<osg::Image> rgba = new osg::Image;
    rgba->allocateImage(40, 30, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    EXPECT_FALSE(sheet.addFrame(0, *rgba));
}

TEST(ContactSheet, PlacesFramesRowByRowFromTheTopLeft)
{
    // Five 40x30 frames reduced to 20x15, in a 3-column grid: two rows.
    ContactSheet sheet(5, 3, 40, 30, 20, osg::Vec4(0, 0, 0, 1));
    EXPECT_EQ(sheet.getColumns(), 3u);
    EXPECT_EQ(sheet.getRows(), 2u);
    EXPECT_EQ(sheet.getTileHeight(), 15);
    const osg::Image& image = *sheet.getImage();
    const int m = ContactSheet::kMargin;
    EXPECT_EQ(image.s(), 3 * (20 + m) + m);
    EXPECT_EQ(image.t(), 2 * (15 + m) + m);

    for (unsigned i = 0; i < 5; ++i)
        ASSERT_TRUE(sheet.addFrame(i, *solidFrame(40, 30, static_cast<unsigned char>(50 * (i + 1)))));
    // Image rows are bottom-first: the top row of tiles is at the highest y.
    const auto tileValue = [&](int column, int rowFromTop) {
        const int x = m + column * (20 + m) + 10;
        const int y = image.t() - (rowFromTop + 1) * (15 + m) + 7;
        return int(image.data(x, y)[0]);
    };
    EXPECT_EQ(tileValue(0, 0), 50);
    EXPECT_EQ(tileValue(2, 0), 150);
    EXPECT_EQ(tileValue(0, 1), 200);
    EXPECT_EQ(tileValue(1, 1), 250);
    EXPECT_EQ(tileValue(2, 1), 0); // no sixth frame: background
    EXPECT_EQ(int(image.data(0, 0)[0]), 0); // margin
}

TEST(ContactSheet, ReducesByAveraging)
{
    // A frame of alternating black and white columns becomes mid grey at half size.
    osg::ref_ptr<osg::Image> stripes = solidFrame(8, 8, 0);
    for (int y = 0; y < 8; ++y)
        for (int x = 1; x < 8; x += 2) std::fill(stripes->data(x, y), stripes->data(x, y) + 3, 255);
    ContactSheet sheet(1, 1, 8, 8, 4, osg::Vec4(0, 0, 0, 1));
    ASSERT_TRUE(sheet.addFrame(0, *stripes));
    const int m = ContactSheet::kMargin;
    EXPECT_EQ(int(sheet.getImage()->data(m + 1, m + 1)[0]), 128);
}
