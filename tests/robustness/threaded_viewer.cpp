/* osgViewer with a multi-threaded threading model (argv[1]: DrawThreadPerContext, CullDrawThreadPerContext or
 * CullThreadPerCameraDrawThreadPerContext) drawing many animating actors in a window, as a simulation would: an
 * ActorGroup updates them on a worker pool while the previous frame is drawn, and the main thread writes DOFs and
 * hides joints between frames. Run under xvfb-run by ctest, and under ThreadSanitizer by
 * scripts/test-sanitizers.sh. Exit status 0 after the frames, 1 if the viewer could not start. */
#include "RobustnessUtil"
#include "ViewerThreadingModel"

#include <osgActor/ActorGroup>

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
    if (!test::startViewer(viewer, model, actors.get())) return 1;
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
