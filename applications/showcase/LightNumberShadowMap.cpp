#include "LightNumberShadowMap.h"

#include <osg/NodeVisitor>
#include <osgShadow/ShadowedScene>

namespace osgActorShowcase {

namespace {

/** The first LightSource below a node whose light has the number. */
class LightSourceFinder : public osg::NodeVisitor
{
public:
    explicit LightSourceFinder(int number)
        : osg::NodeVisitor(osg::NodeVisitor::TRAVERSE_ALL_CHILDREN), _number(number)
    {
    }

    void apply(osg::LightSource& source) override
    {
        if (!found && source.getLight() && source.getLight()->getLightNum() == _number) found = &source;
        traverse(source);
    }

    osg::LightSource* found = nullptr;

private:
    int _number;
};

} // namespace

void LightNumberShadowMap::cull(osgUtil::CullVisitor& cv)
{
    if (!_selected.valid() && _shadowedScene)
    {
        LightSourceFinder finder(_lightNumber);
        _shadowedScene->osg::Group::traverse(finder);
        if (finder.found)
        {
            _selected = finder.found;
            setLight(finder.found);
        }
    }
    osgShadow::ShadowMap::cull(cv);
}

} // namespace osgActorShowcase
