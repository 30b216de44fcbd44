/* osgViewer with a multi-threaded threading model (argv[1]: DrawThreadPerContext, CullDrawThreadPerContext or
 * CullThreadPerCameraDrawThreadPerContext) drawing many animating actors in a window, as a simulation would: an
 * ActorGroup updates them on a worker pool while the previous frame is drawn, and the main thread writes DOFs and
 * hides joints between frames. Run under xvfb-run by ctest, and under ThreadSanitizer by
 * scripts/test-sanitizers.sh. Exit status 0 after the frames, 1 if the viewer could not start. */
#include "RobustnessUtil"

#include <osgActor/ActorGroup>

#include <osgViewer/Viewer>

#include <cstdlib>
#include <iostream>

using namespace osgActor;

int main(int argc, char** argv)
{
    if (argc < 2)
    {
        std::cerr << "usage: " << argv[0] << " <threading model> [frames]\n";
        return 1;
    }
    const std::string modelName = argv[1];
    osgViewer::ViewerBase::ThreadingModel model;
    if (modelName == "DrawThreadPerContext") model = osgViewer::ViewerBase::DrawThreadPerContext;
    else if (modelName == "CullDrawThreadPerContext") model = osgViewer::ViewerBase::CullDrawThreadPerContext;
    else if (modelName == "CullThreadPerCameraDrawThreadPerContext")
        model = osgViewer::ViewerBase::CullThreadPerCameraDrawThreadPerContext;
    else
    {
        std::cerr << "unknown threading model " << modelName << "\n";
        return 1;
    }
    const int frames = argc > 2 ? std::atoi(argv[2]) : 120;

    std::mt19937 random(8);
    osg::ref_ptr<ActorNode> prototype = test::readHumanoid();
    osg::ref_ptr<ActorGroup> actors = new ActorGroup;
    actors->setNumThreads(3);
    for (int a = 0; a < 24; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(prototype.get(), osg::CopyOp::SHALLOW_COPY);
        test::addPlayer(*actor, test::makeRandomClip(*prototype->getDefinition(), random, a));
        actor->setPreTranslation(osg::Vec3d(2.0 * (a % 6), 2.0 * (a / 6), 0.0));
        actors->addChild(actor.get());
    }

    osgViewer::Viewer viewer;
    viewer.setThreadingModel(model);
    viewer.setUpViewInWindow(0, 0, 320, 240);
    viewer.setSceneData(actors.get());
    viewer.realize();
    if (!viewer.isRealized())
    {
        std::cerr << "the viewer did not start (no display?)\n";
        return 1;
    }
    for (int frame = 0; frame < frames && !viewer.done(); ++frame)
    {
        // Between frames, on the main thread (OSG's update thread): what an application does to its actors.
        ActorNode* actor = static_cast<ActorNode*>(actors->getChild(random() % actors->getNumChildren()));
        actor->setDof(random() % actor->getNumDofs(), 0.01 * (random() % 100));
        SkeletonNode* joint = actor->getSkeletonNode(random() % actor->getNumSkeletonNodes());
        joint->setHidden(!joint->getHidden());
        viewer.frame();
    }
    std::cout << "threaded_viewer: " << modelName << ", " << viewer.getFrameStamp()->getFrameNumber()
              << " frames\n";
    return 0;
}
