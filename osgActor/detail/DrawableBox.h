// Internal to the library (not installed, NOT API): a drawable's bounding box in the instanced crowd's hot loops.
// osg::Drawable::getBoundingBox() is inline but large (it computes the box where it is not yet), and GCC inlines it or
// not by how large the file around the loop has grown, a call per part drawn when not; here its common case, the box
// computed already, is a test and a reference, and the other case is OSG's own call.
#ifndef OSGACTOR_DETAIL_DRAWABLEBOX_H
#define OSGACTOR_DETAIL_DRAWABLEBOX_H 1

#include <osg/Drawable>

namespace osgActor {
namespace detail {

struct DrawableBox : osg::Drawable
{
    /** The box osg::Drawable::getBoundingBox() gives. */
    static const osg::BoundingBox& of(const osg::Drawable& drawable)
    {
        // Protected members, read through pointers taken in this class (as any osg::Drawable's).
        bool osg::Node::*const computed = &DrawableBox::_boundingSphereComputed;
        osg::BoundingBox osg::Drawable::*const box = &DrawableBox::_boundingBox;
        return drawable.*computed ? drawable.*box : drawable.getBoundingBox();
    }
};

} // namespace detail
} // namespace osgActor

#endif
