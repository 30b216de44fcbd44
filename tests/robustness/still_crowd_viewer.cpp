/* A still crowd under an InstancedActorGroup before a still camera, in osgViewer with a threading model (argv[1], as
 * osgactor_threaded_viewer takes it, with a draw thread: DrawThreadPerContext or
 * CullThreadPerCameraDrawThreadPerContext) for a number of frames (argv[2]); argv[3] "serial": too few actors for the
 * group's threads. The render graph of one frame is drawn while the next is culled, so the group's frames (their
 * texture buffers of instances) alternate; once each has been filled, no cull may mark a buffer for upload again. The
 * buffers are found in the render graphs the renderer's scene views hold, the draw thread stopped. Run under xvfb-run
 * by ctest and ThreadSanitizer. Exit status 0 when nothing was marked for upload after the first frames, 1 if
 * something was, the frames did not alternate, or the viewer could not start. */
#include "RobustnessUtil"
#include "ViewerThreadingModel"
#include "nodes/CullProbe"

#include <osgActor/InstancedActorGroup>
#include <osgActor/detail/InstancedDraw.h>

#include <osg/TextureBuffer>
#include <osgViewer/Renderer>
#include <osgViewer/Viewer>

#include <iostream>
#include <set>

using namespace osgActor;

namespace {

/** The texture buffers of instances the render graphs of the renderer's scene views read. */
std::set<const osg::Image*> instanceBuffers(osgViewer::Viewer& viewer)
{
    std::set<const osg::Image*> images;
    auto* renderer = dynamic_cast<osgViewer::Renderer*>(viewer.getCamera()->getRenderer());
    if (!renderer) return images;
    for (unsigned k = 0; k < 2; ++k)
    {
        osgUtil::SceneView* view = renderer->getSceneView(k);
        if (!view || !view->getRenderStage()) continue;
        std::vector<test::CulledLeaf> leaves;
        test::collectLeaves(*view->getRenderStage(), leaves);
        for (const test::CulledLeaf& leaf : leaves)
        {
            if (!dynamic_cast<const detail::InstancedDraw*>(leaf.drawable) || leaf.states.empty()) continue;
            const auto* buffer = dynamic_cast<const osg::TextureBuffer*>(leaf.states.back()->getTextureAttribute(
                InstancedActorGroup::kInstanceTextureUnit, osg::StateAttribute::TEXTURE));
            if (buffer && buffer->getImage()) images.insert(buffer->getImage());
        }
    }
    return images;
}

unsigned uploadsOf(const std::set<const osg::Image*>& images)
{
    unsigned count = 0;
    for (const osg::Image* image : images) count += image->getModifiedCount();
    return count;
}

} // namespace

int main(int argc, char** argv)
{
    osgViewer::ViewerBase::ThreadingModel model;
    int frames = 0;
    if (!test::parseThreadedViewerArguments(argc, argv, 60, model, frames)) return 1;
    osg::ref_ptr<ActorNode> prototype = test::readHumanoid();
    osg::ref_ptr<InstancedActorGroup> crowd = new InstancedActorGroup;
    crowd->setNumThreads(2);
    crowd->setMinActorsForParallelCull(12); // on the threads from 12 actors on
    const bool serial = argc > 3 && std::string(argv[3]) == "serial";
    const int numActors = serial ? 8 : 24;
    for (int a = 0; a < numActors; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(prototype.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setPreTranslation(osg::Vec3d(2.0 * (a % 6), 2.0 * (a / 6), 0.0));
        actor->setDof(a % actor->getNumDofs(), 0.3);
        crowd->addChild(actor.get());
    }
    osgViewer::Viewer viewer;
    if (!test::startViewer(viewer, model, crowd.get())) return 1;
    viewer.getCamera()->setViewMatrixAsLookAt(osg::Vec3d(5.0, -14.0, 4.0), osg::Vec3d(5.0, 3.0, 0.9),
                                              osg::Vec3d(0.0, 0.0, 1.0));
    // The first frames cull afresh, keep, and fill each frame once.
    const int warmUp = 8;
    for (int frame = 0; frame < warmUp; ++frame) viewer.frame();
    viewer.stopThreading();
    const std::set<const osg::Image*> buffers = instanceBuffers(viewer);
    const unsigned uploads = uploadsOf(buffers);
    viewer.startThreading();
    for (int frame = warmUp; frame < frames; ++frame) viewer.frame();
    viewer.stopThreading();
    const std::set<const osg::Image*> buffersAfter = instanceBuffers(viewer);
    const unsigned uploadsAfter = uploadsOf(buffersAfter);
    const InstancedActorGroup::Statistics statistics = crowd->getStatistics();
    std::cout << "still_crowd_viewer: " << argv[1] << ", " << viewer.getFrameStamp()->getFrameNumber() << " frames, "
              << buffers.size() << " buffers held, marked for upload " << uploads << " times after " << warmUp
              << " frames and " << uploadsAfter << " at the end; last cull: " << statistics.actorsKept << " of "
              << statistics.actorsInstanced << " actors kept, " << statistics.instances << " instances, "
              << crowd->getNumParallelCulls() << " culls on the threads\n";
    if (buffers.empty() || statistics.actorsKept == 0 || statistics.actorsKept != statistics.actorsInstanced ||
        (serial ? crowd->getNumParallelCulls() != 0 : crowd->getNumParallelCulls() == 0))
    {
        std::cerr << "still_crowd_viewer: the crowd was not drawn instanced, kept, as asked\n";
        return 1;
    }
    // With a draw thread the renderer's two scene views hold the render graphs of two frames, each its own buffer.
    if (buffers.size() != 2)
    {
        std::cerr << "still_crowd_viewer: the frames did not alternate\n";
        return 1;
    }
    if (buffersAfter != buffers || uploadsAfter != uploads)
    {
        std::cerr << "still_crowd_viewer: a still crowd's buffers were marked for upload again\n";
        return 1;
    }
    return 0;
}
