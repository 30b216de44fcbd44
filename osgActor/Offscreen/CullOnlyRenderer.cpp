#include "CullOnlyRenderer.h"

#include <osgUtil/SceneView>

namespace osgActor {

void CullOnlyRenderer::cull_draw()
{
    if (_drawEnabled)
    {
        osgViewer::Renderer::cull_draw();
        return;
    }
    // What osgViewer::Renderer::cull_draw() does up to its draw, less the statistics and GL queries: the scene
    // view takes the frame stamp and the camera's cull settings, then culls (cull callbacks run, the render graph
    // is built and left for the next cull to clear).
    osgUtil::SceneView* sceneView = getSceneView(0);
    if (sceneView == nullptr || getDone()) return;
    updateSceneView(sceneView);
    sceneView->inheritCullSettings(*sceneView->getCamera());
    sceneView->cull();
}

} // namespace osgActor
