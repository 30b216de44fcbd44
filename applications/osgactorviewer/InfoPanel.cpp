#include "InfoPanel.h"

#include <osg/Geode>
#include <osgDB/FileUtils>
#include <osgText/Font>

namespace osgActorViewer {

namespace {

const float kCharacterSize = 13.0f; // pixels
const float kMargin = 10.0f;        // pixels

/** DejaVu Sans (Debian's fonts-dejavu-core) when it is there; otherwise osgText's built-in font. */
osg::ref_ptr<osgText::Font> panelFont()
{
    static const char* const kFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    static osg::ref_ptr<osgText::Font> font =
        osgDB::fileExists(kFontFile) ? osgText::readRefFontFile(kFontFile) : osg::ref_ptr<osgText::Font>();
    return font;
}

osg::ref_ptr<osgText::Text> makeText(osgText::Text::AlignmentType alignment, const osg::Vec4& colour)
{
    osg::ref_ptr<osgText::Text> text = new osgText::Text;
    if (osg::ref_ptr<osgText::Font> font = panelFont()) text->setFont(font.get());
    text->setCharacterSize(kCharacterSize);
    text->setAlignment(alignment);
    text->setColor(colour);
    text->setBackdropType(osgText::Text::OUTLINE); // readable over any scene
    text->setDataVariance(osg::Object::DYNAMIC);   // rewritten while the previous frame may still be drawn
    return text;
}

} // namespace

InfoPanel::InfoPanel(int width, int height)
    : _status(makeText(osgText::Text::LEFT_TOP, osg::Vec4(1.0f, 1.0f, 0.85f, 1.0f))),
      _keys(makeText(osgText::Text::LEFT_BOTTOM, osg::Vec4(0.8f, 0.9f, 1.0f, 1.0f)))
{
    setReferenceFrame(osg::Transform::ABSOLUTE_RF);
    setViewMatrix(osg::Matrixd::identity());
    setClearMask(GL_DEPTH_BUFFER_BIT);
    setRenderOrder(osg::Camera::POST_RENDER);
    setAllowEventFocus(false);

    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    geode->addDrawable(_status.get());
    geode->addDrawable(_keys.get());
    addChild(geode.get());
    resize(width, height);
}

void InfoPanel::setStatus(const std::string& text)
{
    if (_status->getText().createUTF8EncodedString() != text) _status->setText(text);
}

void InfoPanel::setKeys(const std::string& text) { _keys->setText(text); }

void InfoPanel::resize(int width, int height)
{
    setProjectionMatrixAsOrtho2D(0.0, width, 0.0, height);
    _status->setPosition(osg::Vec3(kMargin, float(height) - kMargin, 0.0f));
    _keys->setPosition(osg::Vec3(kMargin, kMargin, 0.0f));
}

} // namespace osgActorViewer
