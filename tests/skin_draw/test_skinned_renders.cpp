// Renders of Cesium Man walking, through OSMesa: on the GPU path in both profiles and on the CPU path, each against its
// reference image (tests/render/references/cesium_man_*.png, looked at), and the paths against one another: the
// skinning program lights and textures the mesh as fixed function does the CPU path's (a rigid mesh of the same
// material), and the core profile's uniforms stand in for the headlight the compatibility profile reads. Under
// osgShadow's ShadowMap the skinned mesh receives shadows on both paths, lit by the scene's lights.
#include "ImageCompare.h"
#include "SkinDrawTestUtil"

#include <osgActor/Offscreen/OffscreenRenderer>

#include <osg/LightSource>
#include <osg/ShapeDrawable>
#include <osgShadow/ShadowMap>
#include <osgShadow/ShadowedScene>

#include <gtest/gtest.h>

#include <iostream>
#include <vector>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Cesium Man at 0.5 s of his walk (stepped from 0 at 30 frames per second), framed, 200 x 240 pixels. */
osg::ref_ptr<osg::Image> renderCesiumMan(SkinnedMesh::SkinningPath path, SkinningProfile profile)
{
    std::string error;
    osg::ref_ptr<OffscreenRenderer> renderer = OffscreenRenderer::create(200, 240, error);
    EXPECT_TRUE(renderer) << error;
    if (!renderer) return nullptr;
    if (profile == SkinningProfile::Core)
    {
        osg::State* state = renderer->getCamera()->getGraphicsContext()->getState();
        state->setUseVertexAttributeAliasing(true);
        state->setUseModelViewAndProjectionUniforms(true);
    }
    const RiggedModelActor read = readCesiumMan(path);
    renderer->setScene(read.sceneNode.get());
    renderer->stepTo(0.5, 30.0);
    renderer->frameScene();
    return renderer->draw();
}

/** How two renders differ, printed: the share of pixels over the tolerance and the largest difference. */
ImageComparison compareRenders(const osg::Image& a, const osg::Image& b, const std::string& what)
{
    const ImageComparison comparison = compareImages(a, b, 2);
    std::cout << what << ": " << comparison.numOverTolerance << " of " << comparison.numPixels
              << " pixels differ by more than 2, largest difference " << comparison.maxChannelDifference << ", PSNR "
              << comparison.psnr << " dB\n";
    return comparison;
}

} // namespace

TEST(SkinnedMeshRenders, CesiumManWalkingMatchesItsReferencesOnBothPathsAndBothProfiles)
{
    const osg::ref_ptr<osg::Image> gpu = renderCesiumMan(SkinnedMesh::GPU_SKINNING, SkinningProfile::Compatibility);
    const osg::ref_ptr<osg::Image> cpu = renderCesiumMan(SkinnedMesh::CPU_SKINNING, SkinningProfile::Compatibility);
    const osg::ref_ptr<osg::Image> core = renderCesiumMan(SkinnedMesh::GPU_SKINNING, SkinningProfile::Core);
    ASSERT_TRUE(gpu && cpu && core);
    EXPECT_TRUE(matchesReference(*gpu, "cesium_man_gpu"));
    EXPECT_TRUE(matchesReference(*cpu, "cesium_man_cpu"));
    EXPECT_TRUE(matchesReference(*core, "cesium_man_gpu_core"));

    // The same picture whichever path skins and lights it, to 2 levels of 255 on every pixel: both light per vertex
    // with the same formula (the CPU path's normals normalised by GL_NORMALIZE, as the program normalises them), the
    // skinned positions agree to about 1e-7 of the model's size (test_gpu_path.cpp), far below a pixel, and what
    // is left is the rounding of two pipelines, llvmpipe's fixed-function shader and ours (one level where measured).
    EXPECT_TRUE(compareRenders(*gpu, *cpu, "GPU (shader) against CPU (fixed function)").matches(0.0));
    EXPECT_TRUE(compareRenders(*core, *gpu, "GPU core profile against compatibility profile").matches(0.0));
}

namespace {

/** Cesium Man at 0.5 s of his walk on a skinning path under an osgShadow::ShadowMap cast by a sun (light 1, in
  * front of him and 45 degrees up, with the viewer's headlight, light 0, also on), seen from the front at the height
  * of his hips, 160 x 200 pixels on a black background; with shade true, a 3 m slab above and in front of him, out of
  * view, between him and the sun. The GPU path's palette in the storage given. */
osg::ref_ptr<osg::Image> renderCesiumManUnderTheSun(SkinnedMesh::SkinningPath path, SkinPaletteStorage storage,
                                                    bool shade)
{
    std::string error;
    osg::ref_ptr<OffscreenRenderer> renderer = OffscreenRenderer::create(160, 200, error);
    EXPECT_TRUE(renderer) << error;
    if (!renderer) return nullptr;

    osg::ref_ptr<osg::LightSource> sun = new osg::LightSource;
    sun->getLight()->setLightNum(1);
    sun->getLight()->setPosition(osg::Vec4(0.0f, -1.0f, 1.0f, 0.0f)); // towards the light: in front, 45 degrees up
    sun->getLight()->setDiffuse(osg::Vec4(0.8f, 0.8f, 0.8f, 1.0f));
    sun->setReferenceFrame(osg::LightSource::RELATIVE_RF);
    osg::ref_ptr<osgShadow::ShadowMap> shadowMap = new osgShadow::ShadowMap;
    shadowMap->setLight(sun.get());
    shadowMap->setTextureSize(osg::Vec2s(512, 512));
    osg::ref_ptr<osgShadow::ShadowedScene> scene = new osgShadow::ShadowedScene(shadowMap.get());
    scene->addChild(sun.get());
    sun->setStateSetModes(*scene->getOrCreateStateSet(), osg::StateAttribute::ON);

    const RiggedModelActor read = readCesiumMan(path);
    read.skinnedMeshes[0]->setPaletteStorage(storage);
    scene->addChild(read.sceneNode.get());
    if (shade)
    {
        osg::ref_ptr<osg::Geode> slab = new osg::Geode;
        slab->addDrawable(new osg::ShapeDrawable(new osg::Box(osg::Vec3(0.0f, -1.6f, 2.4f), 3.0f, 3.0f, 0.1f)));
        scene->addChild(slab.get());
    }
    renderer->setScene(scene.get());
    renderer->setBackground(osg::Vec4(0.0f, 0.0f, 0.0f, 1.0f));
    renderer->setViewMatrixAsLookAt(osg::Vec3d(0.0, -4.5, 0.75), osg::Vec3d(0.0, 0.0, 0.75), osg::Vec3d(0, 0, 1));
    renderer->stepTo(0.5, 30.0);
    return renderer->draw();
}

/** The mean of the red, green and blue levels (0-255) over the pixels that are not black in the mask image. */
double meanLevelWhereDrawn(const osg::Image& image, const osg::Image& mask, unsigned& numPixels)
{
    double sum = 0.0;
    numPixels = 0;
    for (int y = 0; y < image.t(); ++y)
        for (int x = 0; x < image.s(); ++x)
        {
            const osg::Vec4 drawn = mask.getColor(x, y);
            if (drawn.r() + drawn.g() + drawn.b() == 0.0f) continue;
            const osg::Vec4 colour = image.getColor(x, y);
            sum += 255.0 * (colour.r() + colour.g() + colour.b()) / 3.0;
            ++numPixels;
        }
    return numPixels ? sum / numPixels : 0.0;
}

} // namespace

TEST(SkinnedMeshRenders, ASkinnedMeshReceivesTheShadowOfASlabBetweenItAndTheSunOnBothPaths)
{
    struct Variant
    {
        const char* name;
        SkinnedMesh::SkinningPath path;
        SkinPaletteStorage storage;
    };
    // The texture buffer's vertex shader is GLSL 1.50 compatibility, linked with ShadowMap's GLSL 1.10 one.
    const Variant variants[] = {{"GPU path, uniforms", SkinnedMesh::GPU_SKINNING, SkinPaletteStorage::UniformArray},
                                {"GPU path, texture buffer", SkinnedMesh::GPU_SKINNING, SkinPaletteStorage::TextureBuffer},
                                {"CPU path", SkinnedMesh::CPU_SKINNING, SkinPaletteStorage::Automatic}};
    std::vector<osg::ref_ptr<osg::Image>> shadedRenders;
    for (const Variant& variant : variants)
    {
        const osg::ref_ptr<osg::Image> sunlit = renderCesiumManUnderTheSun(variant.path, variant.storage, false);
        const osg::ref_ptr<osg::Image> shaded = renderCesiumManUnderTheSun(variant.path, variant.storage, true);
        ASSERT_TRUE(sunlit && shaded);
        shadedRenders.push_back(shaded);
        unsigned numPixels = 0;
        const double sunlitLevel = meanLevelWhereDrawn(*sunlit, *sunlit, numPixels);
        const double shadedLevel = meanLevelWhereDrawn(*shaded, *sunlit, numPixels);
        std::cout << variant.name << ": mean level over Cesium Man's " << numPixels << " pixels " << sunlitLevel
                  << " in the sun, " << shadedLevel << " in the slab's shadow\n";
        ASSERT_GT(numPixels, 2000u) << variant.name << ": Cesium Man fills a good part of the picture";
        // ShadowMap's fragment shader scales the lit colour (headlight and sun) by 0.5 + 0.5 x (the share of the
        // shadow map's samples that see the sun): under the slab every sample is in shadow, so he is about halved.
        EXPECT_LT(shadedLevel, 0.6 * sunlitLevel) << variant.name << ": the slab's shadow does not fall on him";
        EXPECT_GT(shadedLevel, 0.4 * sunlitLevel) << variant.name;
    }
    // The skinning vertex shader lights him as fixed function lights the CPU path's mesh, for the same fragment shader.
    for (unsigned gpu = 0; gpu < 2; ++gpu)
        EXPECT_TRUE(compareRenders(*shadedRenders[gpu], *shadedRenders[2],
                                   std::string("in the shadow, ") + variants[gpu].name + " against the CPU path")
                        .matches(0.01));
}
