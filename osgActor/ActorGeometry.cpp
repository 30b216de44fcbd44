#include <osgActor/ActorGeometry>
#include <osgActor/GlmOsg>
#include <osgActor/io/AngleAxis>
#include <osgActor/text/Numbers>

#include <osg/BlendFunc>
#include <osg/Geode>
#include <osg/ShapeDrawable>


namespace osgActor {

const char* const kShapeNodeDescription = "osgActor:shape";
const char* const kModelNodeDescriptionPrefix = "osgActor:model ";

namespace {

/** OSG's shapes and colours hold floats: each is read back as the double of the float's shortest text, so that
  * 0.3f gives 0.3, what a file said, which the writer then writes again. */
double fromFloat(float value) { return doubleFromFloatText(value); }

/** Rotations and model placements are doubles, which OSG's text formats read back within a step or two of what
  * they wrote: each is taken as the nearby number (or rotation) of short text a file wrote. */
glm::dquat fromOsgText(const osg::Quat& rotation) { return nearestWrittenRotation(toGlm(rotation)); }
double fromOsgText(double value) { return shortestNear(value, 4); }
glm::dvec3 fromOsgText(const osg::Vec3d& v)
{
    return glm::dvec3(fromOsgText(v.x()), fromOsgText(v.y()), fromOsgText(v.z()));
}

glm::dvec3 fromFloat(const osg::Vec3& v) { return glm::dvec3(fromFloat(v.x()), fromFloat(v.y()), fromFloat(v.z())); }

/** OSG places a cone's centre a quarter of its height above the base; the file places it half way up. */
osg::Vec3d coneCentreOffset(const osg::Quat& rotation, double height)
{
    return rotation * osg::Vec3d(0.0, 0.0, 0.25 * height);
}

osg::ref_ptr<osg::Shape> makeShape(const GeometryDescription& d)
{
    const osg::Vec3 centre = toOsg(d.position);
    const osg::Quat rotation = toOsg(d.rotation);
    const float radius = static_cast<float>(d.radius);
    const float height = static_cast<float>(d.height);
    switch (d.kind)
    {
    case GeometryKind::Box:
    {
        osg::ref_ptr<osg::Box> box = new osg::Box(centre, static_cast<float>(d.size.x), static_cast<float>(d.size.y),
                                                  static_cast<float>(d.size.z));
        box->setRotation(rotation);
        return box;
    }
    case GeometryKind::Sphere: return new osg::Sphere(centre, radius);
    case GeometryKind::Capsule:
    {
        osg::ref_ptr<osg::Capsule> capsule = new osg::Capsule(centre, radius, height);
        capsule->setRotation(rotation);
        return capsule;
    }
    case GeometryKind::Cylinder:
    {
        osg::ref_ptr<osg::Cylinder> cylinder = new osg::Cylinder(centre, radius, height);
        cylinder->setRotation(rotation);
        return cylinder;
    }
    case GeometryKind::Cone:
    {
        const osg::Vec3d base = toOsg(d.position) - coneCentreOffset(rotation, d.height);
        osg::ref_ptr<osg::Cone> cone = new osg::Cone(osg::Vec3(base), radius, height);
        cone->setRotation(rotation);
        return cone;
    }
    case GeometryKind::Model: break;
    }
    return nullptr;
}

bool describeShape(const osg::Shape& shape, GeometryDescription& d)
{
    if (const osg::Box* box = dynamic_cast<const osg::Box*>(&shape))
    {
        d.kind = GeometryKind::Box;
        d.size = fromFloat(box->getHalfLengths() * 2.0f); // doubling a float is exact
        d.position = fromFloat(box->getCenter());
        d.rotation = fromOsgText(box->getRotation());
    }
    else if (const osg::Sphere* sphere = dynamic_cast<const osg::Sphere*>(&shape))
    {
        d.kind = GeometryKind::Sphere;
        d.radius = fromFloat(sphere->getRadius());
        d.position = fromFloat(sphere->getCenter());
    }
    else if (const osg::Capsule* capsule = dynamic_cast<const osg::Capsule*>(&shape))
    {
        d.kind = GeometryKind::Capsule;
        d.radius = fromFloat(capsule->getRadius());
        d.height = fromFloat(capsule->getHeight());
        d.position = fromFloat(capsule->getCenter());
        d.rotation = fromOsgText(capsule->getRotation());
    }
    else if (const osg::Cylinder* cylinder = dynamic_cast<const osg::Cylinder*>(&shape))
    {
        d.kind = GeometryKind::Cylinder;
        d.radius = fromFloat(cylinder->getRadius());
        d.height = fromFloat(cylinder->getHeight());
        d.position = fromFloat(cylinder->getCenter());
        d.rotation = fromOsgText(cylinder->getRotation());
    }
    else if (const osg::Cone* cone = dynamic_cast<const osg::Cone*>(&shape))
    {
        d.kind = GeometryKind::Cone;
        d.radius = fromFloat(cone->getRadius());
        d.height = fromFloat(cone->getHeight());
        d.rotation = fromOsgText(cone->getRotation());
        // Rounded to float like the other positions, so the offset's round-off does not show in the file.
        d.position =
            fromFloat(osg::Vec3(osg::Vec3d(cone->getCenter()) + coneCentreOffset(cone->getRotation(), d.height)));
    }
    else
    {
        return false;
    }
    return true;
}

bool hasDescription(const osg::Node& node, const std::string& text)
{
    for (const std::string& description : node.getDescriptions())
        if (description == text) return true;
    return false;
}

} // namespace

osg::ref_ptr<osg::Geode> createShapeNode(const GeometryDescription& shape)
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    osg::ref_ptr<osg::ShapeDrawable> drawable = new osg::ShapeDrawable(makeShape(shape).get());
    drawable->setColor(osg::Vec4(static_cast<float>(shape.color.r), static_cast<float>(shape.color.g),
                                 static_cast<float>(shape.color.b), static_cast<float>(shape.color.a)));
    geode->addDrawable(drawable.get());
    geode->addDescription(kShapeNodeDescription);
    if (shape.color.a < 1.0)
    {
        osg::StateSet* state = geode->getOrCreateStateSet();
        state->setAttributeAndModes(new osg::BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA));
        state->setRenderingHint(osg::StateSet::TRANSPARENT_BIN);
    }
    return geode;
}

osg::ref_ptr<osg::PositionAttitudeTransform> createModelNode(const GeometryDescription& model, osg::Node* loaded)
{
    osg::ref_ptr<osg::PositionAttitudeTransform> transform = new osg::PositionAttitudeTransform;
    transform->setPosition(toOsg(model.position));
    transform->setAttitude(toOsg(model.rotation));
    transform->setScale(osg::Vec3d(model.scale, model.scale, model.scale));
    transform->setDataVariance(osg::Object::DYNAMIC);
    transform->addDescription(kModelNodeDescriptionPrefix + model.file);
    if (model.scale != 1.0) transform->getOrCreateStateSet()->setMode(GL_RESCALE_NORMAL, osg::StateAttribute::ON);
    if (loaded) transform->addChild(loaded);
    return transform;
}

bool describeGeometryNode(const osg::Node& node, GeometryDescription& description)
{
    if (const osg::PositionAttitudeTransform* transform = dynamic_cast<const osg::PositionAttitudeTransform*>(&node))
    {
        const std::string prefix = kModelNodeDescriptionPrefix;
        for (const std::string& text : transform->getDescriptions())
        {
            if (text.compare(0, prefix.size(), prefix) != 0) continue;
            description = GeometryDescription();
            description.kind = GeometryKind::Model;
            description.file = text.substr(prefix.size());
            description.position = fromOsgText(transform->getPosition());
            description.rotation = fromOsgText(transform->getAttitude());
            description.scale = fromOsgText(transform->getScale().x());
            return !description.file.empty();
        }
        return false;
    }
    const osg::Geode* geode = node.asGeode();
    if (!geode || !hasDescription(node, kShapeNodeDescription) || geode->getNumDrawables() != 1) return false;
    const osg::ShapeDrawable* drawable = dynamic_cast<const osg::ShapeDrawable*>(geode->getDrawable(0));
    if (!drawable || !drawable->getShape()) return false;
    description = GeometryDescription();
    if (!describeShape(*drawable->getShape(), description)) return false;
    const osg::Vec4& color = drawable->getColor();
    description.color =
        glm::dvec4(fromFloat(color.r()), fromFloat(color.g()), fromFloat(color.b()), fromFloat(color.a()));
    return true;
}

} // namespace osgActor
