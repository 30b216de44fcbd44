/* osgViewer with a multi-threaded threading model (argv[1]: DrawThreadPerContext, CullDrawThreadPerContext or
 * CullThreadPerCameraDrawThreadPerContext) drawing skinned Cesium Men through two cameras (a slave beside the master:
 * under CullThreadPerCamera... two cull threads meet the same meshes in one frame): every actor a shallow copy of one
 * (they share one SkinnedMesh), half of them skinned on the CPU, and as many rigid ones (Cesium Man's skeleton with a
 * stick figure, no skin), all updated by an ActorGroup on worker threads while the previous frame is drawn, their
 * skins' matrices and bounds computed there too, and culled with the group's parallel preparation (one camera's cull
 * at a time; the other's serially); the main thread turns actors' paths between frames. The slave is added before
 * the viewer starts its threads, so that each camera is culled where the model says (a camera added later is culled
 * on the draw thread, alongside the next frame's update). Run under xvfb-run by ctest and under ThreadSanitizer by
 * scripts/test-sanitizers.sh. With "instanced" after the frame count, an InstancedActorGroup: the GPU-skinned actors'
 * meshes drawn with one instanced draw from per-frame texture buffers of their palettes, which the next frame's cull
 * must not write while this one draws them, and actors going to the ordinary path and back as they change path.
 * Exit status 0 after the frames (and every actor's mesh skinned or uploaded once per frame it was seen), 1
 * otherwise. */
#include "ViewerThreadingModel"

#include <osgActor/ActorGroup>
#include <osgActor/InstancedActorGroup>
#include <osgActor/RiggedModelActor>

#include <osgViewer/Renderer>
#include <osgViewer/Viewer>

#include <cstdlib>
#include <iostream>

using namespace osgActor;

int main(int argc, char** argv)
{
    osgViewer::ViewerBase::ThreadingModel model;
    int frames = 0;
    if (!test::parseThreadedViewerArguments(argc, argv, 60, model, frames)) return 1;
    const std::string modelName = argv[1];

    std::string error;
    const RiggedModelActor read = readRiggedModelActor(std::string(OSGACTOR_TEST_DATA_DIR) +
                                                           "/models/CesiumMan/CesiumMan.gltf",
                                                       RiggedModelActorOptions(), error);
    if (!read.actor)
    {
        std::cerr << error << "\n";
        return 1;
    }
    RiggedModelActorOptions figureOptions;
    figureOptions.addFigure = true;
    const RiggedModelActor figure = readRiggedModelActor(std::string(OSGACTOR_TEST_DATA_DIR) +
                                                             "/models/CesiumMan/CesiumMan.gltf",
                                                         figureOptions, error);
    osg::Node* figureSkins =
        figure.actor && !figure.skinnedMeshes.empty() ? figure.skinnedMeshes[0]->getParent(0) : nullptr;
    if (!figureSkins)
    {
        std::cerr << error << "\n";
        return 1;
    }
    figure.actor->removeChild(figureSkins); // rigid: the stick figure on the joints only
    const bool instanced = argc > 3 && std::string(argv[3]) == "instanced";
    osg::ref_ptr<ActorGroup> actors = instanced ? new InstancedActorGroup : new ActorGroup;
    actors->setNumThreads(2);
    actors->setMinActorsForParallelCull(1);
    const int numSkinned = 12;
    for (int a = 0; a < 2 * numSkinned; ++a)
    {
        const bool skinned = a < numSkinned;
        osg::ref_ptr<ActorNode> actor =
            osg::clone((skinned ? read : figure).actor.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setPreTranslation(osg::Vec3d(0.8 * (a % 4), 0.8 * (a / 4), 0.0));
        if (a % 2) setSkinningPath(*actor, SkinnedMesh::CPU_SKINNING);
        actors->addChild(actor.get());
    }

    osgViewer::Viewer viewer;
    viewer.setThreadingModel(model);
    viewer.setUpViewInWindow(0, 0, 320, 240);
    viewer.setSceneData(actors.get());
    // A second camera on the same window: its own cull (on its own thread with CullThreadPerCamera...).
    osg::ref_ptr<osg::Camera> slave = new osg::Camera;
    slave->setGraphicsContext(viewer.getCamera()->getGraphicsContext());
    slave->setViewport(new osg::Viewport(0, 0, 160, 120));
    slave->setClearMask(GL_DEPTH_BUFFER_BIT);
    viewer.addSlave(slave.get(), osg::Matrixd::scale(0.5, 0.5, 1.0), osg::Matrixd());
    viewer.realize();
    if (!viewer.isRealized())
    {
        std::cerr << "the viewer did not start (no display?)\n";
        return 1;
    }
    // Only CullDrawThreadPerContext culls on the graphics thread, after the previous frame's draw.
    const bool graphicsThreadCulls = model == osgViewer::ViewerBase::CullDrawThreadPerContext;
    for (osg::Camera* camera : {viewer.getCamera(), slave.get()})
    {
        const osgViewer::Renderer* renderer = dynamic_cast<const osgViewer::Renderer*>(camera->getRenderer());
        if (!renderer || renderer->getGraphicsThreadDoesCull() != graphicsThreadCulls)
        {
            std::cerr << "a camera is not culled where " << modelName << " culls\n";
            return 1;
        }
    }
    viewer.getCamera()->setViewMatrixAsLookAt(osg::Vec3d(1.2, -5.0, 1.5), osg::Vec3d(1.2, 0.8, 0.6),
                                              osg::Vec3d(0, 0, 1));
    // With "instanced": the culls, among those seen finished after a frame, that drew the GPU-skinned men instanced
    // and the others ordinarily. (Under CullThreadPerCamera... the cull that finished last may be one that met the
    // actors while the other camera culled them, and took them all ordinarily, by design.)
    unsigned mixedCulls = 0;
    for (int frame = 0; frame < frames && !viewer.done(); ++frame)
    {
        // Between frames, on the main thread (OSG's update thread): an actor changes path.
        ActorNode* actor = static_cast<ActorNode*>(actors->getChild(static_cast<unsigned>(frame % numSkinned)));
        setSkinningPath(*actor, frame % 3 ? SkinnedMesh::CPU_SKINNING : SkinnedMesh::GPU_SKINNING);
        viewer.frame();
        if (!instanced) continue;
        const InstancedActorGroup::Statistics statistics = static_cast<InstancedActorGroup&>(*actors).getStatistics();
        if (statistics.skinnedDraws > 0 && statistics.skinnedInstances > 0 && statistics.actorsOrdinary > 0)
            ++mixedCulls;
    }
    viewer.stopThreading();
    const SkinnedMesh& mesh = *read.skinnedMeshes[0];
    unsigned long long work = 0, updates = 0;
    for (int a = 0; a < numSkinned; ++a)
    {
        const SkinnedMesh::Statistics statistics = mesh.getStatistics(*static_cast<ActorNode*>(actors->getChild(static_cast<unsigned>(a))));
        work += statistics.cpuSkinnings + statistics.paletteUploads;
        updates += statistics.matrixUpdates;
        if (statistics.cpuSkinnings + statistics.paletteUploads > statistics.matrixUpdates)
        {
            std::cerr << "actor " << a << " was skinned more often than it was updated\n";
            return 1;
        }
    }
    std::cout << "skinned_threaded_viewer: " << modelName << (instanced ? ", instanced, " : ", ")
              << viewer.getFrameStamp()->getFrameNumber() << " frames, " << updates << " matrix updates, " << work
              << " skinnings or uploads, " << actors->getNumParallelCulls() << " culls prepared on the group's threads\n";
    if (instanced)
    {
        // The group's cull takes its actors itself (a camera whose cull meets it while another culls it gets the
        // ordinary traversal): culls drew the GPU-skinned men instanced and the others ordinarily.
        const InstancedActorGroup::Statistics statistics = static_cast<InstancedActorGroup&>(*actors).getStatistics();
        std::cout << "last cull: " << statistics.actorsInstanced << " actors instanced, " << statistics.actorsOrdinary
                  << " ordinarily, " << statistics.actorsOutOfView << " out of view, " << statistics.skinnedDraws
                  << " skinned draws of " << statistics.skinnedInstances << " instances; " << mixedCulls
                  << " frames ended with such a cull\n";
        if (mixedCulls == 0)
        {
            std::cerr << "the skinned meshes were not drawn instanced\n";
            return 1;
        }
        return work > 0 ? 0 : 1;
    }
    if (actors->getNumParallelCulls() == 0)
    {
        std::cerr << "no cull was prepared on the group's threads\n";
        return 1;
    }
    return work > 0 ? 0 : 1;
}
