/* osgactorviewer: the on-screen text panel. */
#ifndef OSGACTORVIEWER_INFOPANEL_H
#define OSGACTORVIEWER_INFOPANEL_H 1

#include <osg/Camera>
#include <osgText/Text>

#include <string>

namespace osgActorViewer {

/** A head-up display: a status text (actor, clip, time, frame rate) at the top left and the list of keys at the
  * bottom left, in a camera drawn after the scene with a fixed pixel projection. Keeps its size in pixels when the
  * window is resized (call resize()). */
class InfoPanel : public osg::Camera
{
public:
    InfoPanel(int width, int height);

    void setStatus(const std::string& text);
    void setKeys(const std::string& text);
    /** Window size in pixels. */
    void resize(int width, int height);

    void setPanelVisible(bool visible) { setNodeMask(visible ? ~0u : 0u); }
    bool getPanelVisible() const { return getNodeMask() != 0u; }

protected:
    ~InfoPanel() override = default;

    osg::ref_ptr<osgText::Text> _status;
    osg::ref_ptr<osgText::Text> _keys;
};

} // namespace osgActorViewer

#endif
