/* osgActor::Offscreen (not installed): the camera's renderer, which can cull a frame without drawing it. */
#ifndef OSGACTOR_OFFSCREEN_CULLONLYRENDERER_H
#define OSGACTOR_OFFSCREEN_CULLONLYRENDERER_H 1

#include <osgViewer/Renderer>

namespace osgActor {

/** osgViewer's single-threaded renderer, with one switch: with drawing off, a frame is culled and not drawn.
  *
  * Some of OSG runs in the cull traversal, not the update traversal: osgParticle's emitters, programs and
  * ParticleSystemUpdater advance by the frame stamp's time from their cull traversal, and draw std::rand() there.
  * A frame that is stepped through but not shown must still be culled, so that a scene brought to time t shows
  * what a viewer that drew every frame up to t shows; drawing it (the expensive part in software GL) is not
  * needed. */
class CullOnlyRenderer : public osgViewer::Renderer
{
public:
    explicit CullOnlyRenderer(osg::Camera* camera) : osgViewer::Renderer(camera) {}

    void setDrawEnabled(bool enabled) { _drawEnabled = enabled; }
    bool getDrawEnabled() const { return _drawEnabled; }

    /** The viewer's single-threaded path: cull then draw, or the cull alone while drawing is off. */
    void cull_draw() override;

protected:
    ~CullOnlyRenderer() override = default;

private:
    bool _drawEnabled = true;
};

} // namespace osgActor

#endif
