// Renders of Cesium Man walking, through OSMesa: on the GPU path in both profiles and on the CPU path, each against its
// reference image (tests/render/references/cesium_man_*.png, looked at), and the paths against one another: the
// skinning program lights and textures the mesh as fixed function does the CPU path's (a rigid mesh of the same
// material), and the core profile's uniforms stand in for the headlight the compatibility profile reads.
#include "ImageCompare.h"
#include "SkinDrawTestUtil"

#include <osgActor/Offscreen/OffscreenRenderer>

#include <gtest/gtest.h>

#include <iostream>

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
