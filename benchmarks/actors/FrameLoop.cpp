#include "FrameLoop"

#include <osgUtil/RenderStage>
#include <osgUtil/Statistics>

#include <algorithm>

namespace bench {

FrameLoop::FrameLoop(osg::Node* scene, bool withCull, NearFar nearFar, unsigned framesInFlight)
    : _scene(scene), _stamp(new osg::FrameStamp), _update(new osgUtil::UpdateVisitor)
{
    _update->setFrameStamp(_stamp.get());
    if (!withCull) return;
    for (unsigned k = 0; k < std::max(framesInFlight, 1u); ++k)
    {
        osg::ref_ptr<osgUtil::SceneView> sceneView = new osgUtil::SceneView;
        sceneView->setDefaults(osgUtil::SceneView::NO_SCENEVIEW_LIGHT);
        sceneView->setSceneData(scene);
        sceneView->setFrameStamp(_stamp.get());
        sceneView->setViewport(0, 0, 1280, 720);
        // Far enough to see every actor of the largest scene (a row of 1000 walking in place at the origin).
        sceneView->setProjectionMatrixAsPerspective(45.0, 1280.0 / 720.0, 0.1, 1000.0);
        sceneView->setViewMatrixAsLookAt(osg::Vec3d(0, -8, 1), osg::Vec3d(0, 0, 1), osg::Vec3d(0, 0, 1));
        // Otherwise SceneView's default, which is osgViewer's: near and far computed from bounding volumes.
        if (nearFar == NearFar::NotComputed)
            sceneView->getCullVisitor()->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
        _sceneViews.push_back(sceneView);
    }
}

void FrameLoop::frame()
{
    ++_frameNumber;
    _stamp->setFrameNumber(_frameNumber);
    _stamp->setSimulationTime(_frameNumber / 60.0);
    _stamp->setReferenceTime(_frameNumber / 60.0);
    _update->setTraversalNumber(_frameNumber);
    _scene->accept(*_update);
    if (_sceneViews.empty()) return;
    _lastCulled = _sceneViews[_frameNumber % _sceneViews.size()].get();
    _lastCulled->cull();
}

double FrameLoop::lastNear() const
{
    return _lastCulled ? _lastCulled->getCullVisitor()->getCalculatedNearPlane() : 0.0;
}

double FrameLoop::lastFar() const
{
    return _lastCulled ? _lastCulled->getCullVisitor()->getCalculatedFarPlane() : 0.0;
}

unsigned FrameLoop::lastDrawables() const
{
    if (!_lastCulled) return 0;
    osgUtil::Statistics statistics;
    _lastCulled->getRenderStage()->getStats(statistics);
    return statistics.numDrawables;
}

} // namespace bench
