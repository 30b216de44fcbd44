/* osgViewer with a multi-threaded threading model (argv[1]: DrawThreadPerContext, CullDrawThreadPerContext or
 * CullThreadPerCameraDrawThreadPerContext) drawing many animating actors in a window, as a simulation would: an
 * ActorGroup updates them on a worker pool while the previous frame is drawn, and the main thread writes DOFs and
 * hides joints between frames. With "instanced" after the frame count, an InstancedActorGroup: the actors' parts
 * drawn instanced from per-frame texture buffers that the next frame's cull must not write while this one draws
 * them, and actors going to the ordinary path and back as their joints are hidden and shown. Run under xvfb-run by ctest, and under ThreadSanitizer by
 * scripts/test-sanitizers.sh. Exit status 0 after the frames, 1 if the viewer could not start. */
#include "RobustnessUtil"
#include "ViewerThreadingModel"

#include <osgActor/ActorGroup>
#include <osgActor/InstancedActorGroup>

#include <osgViewer/Viewer>

#include <cstdlib>
#include <iostream>

using namespace osgActor;

int main(int argc, char** argv)
{
    osgViewer::ViewerBase::ThreadingModel model;
    int frames = 0;
    if (!test::parseThreadedViewerArguments(argc, argv, 120, model, frames)) return 1;
    const std::string modelName = argv[1];

    std::mt19937 random(8);
    osg::ref_ptr<ActorNode> prototype = test::readHumanoid();
    const bool instanced = argc > 3 && std::string(argv[3]) == "instanced";
    osg::ref_ptr<ActorGroup> actors = instanced ? new InstancedActorGroup : new ActorGroup;
    actors->setNumThreads(3);
    if (instanced) actors->setMinActorsForParallelCull(1); // the instanced cull on the threads too
    for (int a = 0; a < 24; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(prototype.get(), osg::CopyOp::SHALLOW_COPY);
        test::addPlayer(*actor, test::makeRandomClip(*prototype->getDefinition(), random, a));
        actor->setPreTranslation(osg::Vec3d(2.0 * (a % 6), 2.0 * (a / 6), 0.0));
        actors->addChild(actor.get());
    }

    osgViewer::Viewer viewer;
    if (!test::startViewer(viewer, model, actors.get())) return 1;
    // Instanced, the camera frames the crowd (6 x 4 actors, 2 m apart), so that its parts are drawn.
    if (instanced)
        viewer.getCamera()->setViewMatrixAsLookAt(osg::Vec3d(5.0, -14.0, 4.0), osg::Vec3d(5.0, 3.0, 0.9),
                                                  osg::Vec3d(0.0, 0.0, 1.0));
    for (int frame = 0; frame < frames && !viewer.done(); ++frame)
    {
        // Between frames, on the main thread (OSG's update thread): what an application does to its actors.
        ActorNode* actor = static_cast<ActorNode*>(actors->getChild(random() % actors->getNumChildren()));
        actor->setDof(random() % actor->getNumDofs(), 0.01 * (random() % 100));
        // Instanced, joints are hidden in every fourth actor only, so that most of the crowd stays instanced.
        if (instanced) actor = static_cast<ActorNode*>(actors->getChild(4 * (random() % 6)));
        SkeletonNode* joint = actor->getSkeletonNode(random() % actor->getNumSkeletonNodes());
        joint->setHidden(!joint->getHidden());
        viewer.frame();
    }
    std::cout << "threaded_viewer: " << modelName << (instanced ? ", instanced, " : ", ") << viewer.getFrameStamp()->getFrameNumber()
              << " frames\n";
    if (instanced)
    {
        const InstancedActorGroup::Statistics statistics = static_cast<InstancedActorGroup&>(*actors).getStatistics();
        std::cout << "last cull: " << statistics.actorsInstanced << " actors instanced, " << statistics.actorsOrdinary
                  << " ordinarily, " << statistics.actorsOutOfView << " out of view, " << statistics.instances
                  << " instances in " << statistics.draws << " draws\n";
    }
    return 0;
}
