#include <osgActor/detail/ChildrenBound.h>

#include <cfloat>
#include <cmath>
#include <cstring>

namespace osgActor {
namespace detail {

namespace {

bool countsInUnion(const osg::Node& child)
{
    const osg::Transform* transform = child.asTransform();
    return !transform || transform->getReferenceFrame() == osg::Transform::RELATIVE_RF;
}

typedef float FourFloats __attribute__((vector_size(16)));
/** The same at a float's alignment, to load a sphere where it is. */
typedef float UnalignedFourFloats __attribute__((vector_size(16), aligned(4)));

/** A sphere's centre in the first three lanes, its radius in the last. */
inline FourFloats lanesOf(const osg::BoundingSphere& sphere)
{
    static_assert(sizeof(osg::BoundingSphere) == sizeof(FourFloats), "a sphere is its centre and radius");
    return *reinterpret_cast<const UnalignedFourFloats*>(&sphere);
}

} // namespace

osg::BoundingSphere unionOfHeld(const CountingSpheres& spheres)
{
    // osg::BoundingBox::expandBy(const BoundingSphere&) for the three axes at once: each side moved where the sphere's
    // passes it (a comparison with a NaN moves nothing, as there), spheres with no valid radius left out.
    FourFloats low = {FLT_MAX, FLT_MAX, FLT_MAX, FLT_MAX};
    FourFloats high = -low;
    for (std::size_t i = 0; i < spheres.count; ++i)
    {
        const float radius = spheres.at[i]->radius();
        if (!(radius >= 0.0f)) continue;
        const FourFloats sphere = lanesOf(*spheres.at[i]);
        const FourFloats radii = {radius, radius, radius, radius};
        const FourFloats sphereLow = sphere - radii, sphereHigh = sphere + radii;
        low = sphereLow < low ? sphereLow : low;
        high = sphereHigh > high ? sphereHigh : high;
    }
    if (!(high[0] >= low[0] && high[1] >= low[1] && high[2] >= low[2])) return osg::BoundingSphere();
    // The box's centre, then osg::BoundingSphere::expandRadiusBy() from a radius of 0.
    const FourFloats centre = (low + high) * 0.5f;
    float radius = 0.0f;
    for (std::size_t i = 0; i < spheres.count; ++i)
    {
        const float sphereRadius = spheres.at[i]->radius();
        if (!(sphereRadius >= 0.0f)) continue;
        const FourFloats d = lanesOf(*spheres.at[i]) - centre;
        const FourFloats squares = d * d;
        const float reach = std::sqrt(squares[0] + squares[1] + squares[2]) + sphereRadius;
        if (reach > radius) radius = reach;
    }
    return osg::BoundingSphere(osg::Vec3f(centre[0], centre[1], centre[2]), radius);
}

osg::BoundingSphere unionOfChildren(const osg::NodeList& children)
{
    osg::BoundingBox box;
    for (const osg::ref_ptr<osg::Node>& child : children)
        if (countsInUnion(*child)) box.expandBy(child->getBound());
    if (!box.valid()) return osg::BoundingSphere();
    osg::BoundingSphere sphere(box.center(), 0.0f);
    for (const osg::ref_ptr<osg::Node>& child : children)
        if (countsInUnion(*child)) sphere.expandRadiusBy(child->getBound());
    return sphere;
}

} // namespace detail
} // namespace osgActor
