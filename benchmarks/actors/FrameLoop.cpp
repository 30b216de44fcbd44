#include "FrameLoop"

#include <osgUtil/RenderStage>
#include <osgUtil/Statistics>

namespace bench {

FrameLoop::FrameLoop(osg::Node* scene, bool withCull, NearFar nearFar)
    : _scene(scene), _stamp(new osg::FrameStamp), _update(new osgUtil::UpdateVisitor)
{
    _update->setFrameStamp(_stamp.get());
    if (!withCull) return;
    _sceneView = new osgUtil::SceneView;
    _sceneView->setDefaults(osgUtil::SceneView::NO_SCENEVIEW_LIGHT);
    _sceneView->setSceneData(scene);
    _sceneView->setFrameStamp(_stamp.get());
    _sceneView->setViewport(0, 0, 1280, 720);
    // Far enough to see every actor of the largest scene (a row of 1000 walking in place at the origin).
    _sceneView->setProjectionMatrixAsPerspective(45.0, 1280.0 / 720.0, 0.1, 1000.0);
    _sceneView->setViewMatrixAsLookAt(osg::Vec3d(0, -8, 1), osg::Vec3d(0, 0, 1), osg::Vec3d(0, 0, 1));
    // Otherwise SceneView's default, which is osgViewer's: near and far computed from bounding volumes.
    if (nearFar == NearFar::NotComputed)
        _sceneView->getCullVisitor()->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
}

void FrameLoop::frame()
{
    ++_frameNumber;
    _stamp->setFrameNumber(_frameNumber);
    _stamp->setSimulationTime(_frameNumber / 60.0);
    _stamp->setReferenceTime(_frameNumber / 60.0);
    _update->setTraversalNumber(_frameNumber);
    _scene->accept(*_update);
    if (_sceneView.valid()) _sceneView->cull();
}

double FrameLoop::lastNear() const
{
    return _sceneView.valid() ? _sceneView->getCullVisitor()->getCalculatedNearPlane() : 0.0;
}

double FrameLoop::lastFar() const
{
    return _sceneView.valid() ? _sceneView->getCullVisitor()->getCalculatedFarPlane() : 0.0;
}

unsigned FrameLoop::lastDrawables() const
{
    if (!_sceneView.valid()) return 0;
    osgUtil::Statistics statistics;
    _sceneView->getRenderStage()->getStats(statistics);
    return statistics.numDrawables;
}

} // namespace bench
