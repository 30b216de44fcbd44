/* osgActorShowcase: osgShadow's ShadowMap for the light of a given number, which a scene file can keep. */
#ifndef OSGACTORSHOWCASE_LIGHTNUMBERSHADOWMAP_H
#define OSGACTORSHOWCASE_LIGHTNUMBERSHADOWMAP_H 1

#include "Export.h"

#include <osg/LightSource>
#include <osg/observer_ptr>
#include <osgShadow/ShadowMap>

namespace osgActorShowcase {

/** osgShadow::ShadowMap casting the shadows of the light numbered getLightNumber() (GL_LIGHT0 + n), found among the
  * LightSources of its shadowed scene. OSG's ShadowMap keeps the light it is given only in memory (its file wrapper
  * has no light) and otherwise takes the last light of the frame, which may be a viewer's headlight: then the
  * shadows fall straight away from the camera, hidden behind what casts them. The number is written to .osgt/.osgb
  * (ShowcaseWrappers.cpp). Without such a light it does what ShadowMap does. */
class OSGACTORSHOWCASE_EXPORT LightNumberShadowMap : public osgShadow::ShadowMap
{
public:
    LightNumberShadowMap() = default;
    LightNumberShadowMap(const LightNumberShadowMap& shadowMap, const osg::CopyOp& copyop = osg::CopyOp::SHALLOW_COPY)
        : osgShadow::ShadowMap(shadowMap, copyop), _lightNumber(shadowMap._lightNumber)
    {
    }

    META_Object(osgActorShowcase, LightNumberShadowMap);

    void setLightNumber(int number) { _lightNumber = number; }
    int getLightNumber() const { return _lightNumber; }

    /** Selects the light of the number (once found, for as long as its LightSource lives), then ShadowMap's cull. */
    void cull(osgUtil::CullVisitor& cv) override;

protected:
    ~LightNumberShadowMap() override = default;

    int _lightNumber = 0;
    osg::observer_ptr<osg::LightSource> _selected;
};

} // namespace osgActorShowcase

#endif
