// Internal to the library (not installed, NOT API): one geometry drawn once for many instances (InstancedActorGroup,
// issue 28). The geometry is the user's, shared with every actor that hangs it below a joint and with the ordinary
// path: it is not changed (no instance count set on its primitive sets, which another context or the ordinary path
// may draw at the same moment). InstancedDraw sets up the geometry's arrays as osg::Geometry does, then issues each
// primitive set as glDrawArraysInstanced / glDrawElementsInstanced for the instances of this frame, whose data (a
// model-view matrix, and a skinned mesh's palette after it) the vertex shader reads from the frame's texture buffer
// from the given base (InstanceData.glsl).
#ifndef OSGACTOR_DETAIL_INSTANCEDDRAW_H
#define OSGACTOR_DETAIL_INSTANCEDDRAW_H 1

#include <osgActor/detail/InstanceBufferLimit.h>

#include <osg/Geometry>

namespace osgActor {
namespace detail {

class InstancedDraw : public osg::Drawable
{
public:
    InstancedDraw();

    /** Whether a geometry can be drawn instanced: primitive sets of the kinds drawn here (arrays, array lengths,
      * elements of any index type), none instanced already, no draw callback of its own, and no colour per vertex. */
    static bool canDraw(const osg::Geometry& geometry);

    /** Draws geometry for count instances whose data start at texel base, texelsPerInstance texels each. */
    void set(const osg::Geometry* geometry, int base, unsigned count, int texelsPerInstance = 4);
    /** The skin's bind scale a dual-quaternion mesh's program reads (osgActor_bindScale), set with the draw's base. */
    void setBindScale(float bindScale) { _bindScale = bindScale; }
    /** The limit this draw's context reports its GL_MAX_TEXTURE_BUFFER_SIZE to, at its first draw. */
    void setBufferLimit(InstanceBufferLimit* limit) { _limit = limit; }
    const osg::Geometry* getGeometry() const { return _geometry.get(); }
    unsigned getNumInstances() const { return _count; }
    int getBase() const { return _base; }
    int getTexelsPerInstance() const { return _texelsPerInstance; }

    void drawImplementation(osg::RenderInfo& renderInfo) const override;

    const char* libraryName() const override { return "osgActor"; }
    const char* className() const override { return "InstancedDraw"; }
    osg::Object* cloneType() const override { return new InstancedDraw; }
    osg::Object* clone(const osg::CopyOp&) const override { return new InstancedDraw; }

protected:
    ~InstancedDraw() override = default;

private:
    osg::ref_ptr<const osg::Geometry> _geometry;
    int _base;
    unsigned _count;
    int _texelsPerInstance;
    float _bindScale;
    osg::ref_ptr<InstanceBufferLimit> _limit;
};

} // namespace detail
} // namespace osgActor

#endif
