// The osgAnimation converter's geometry (OsgAnimationScene): OSG geometry as RiggedModel primitives, OSG state as its
// materials and images.
#include "OsgAnimationScene"

#include <osg/CullFace>
#include <osg/Material>
#include <osg/Texture>
#include <osg/TriangleIndexFunctor>

#include <algorithm>
#include <cmath>

namespace osgActor {
namespace osganimation {

namespace {

/** Collects the triangles osg::TriangleIndexFunctor finds in a geometry's primitive sets. */
struct TriangleCollector
{
    std::vector<std::uint32_t>* indices = nullptr;
    void operator()(unsigned a, unsigned b, unsigned c) { indices->insert(indices->end(), {a, b, c}); }
};

template <class Vec>
bool allFinite(const std::vector<Vec>& values)
{
    for (const Vec& v : values)
        for (int i = 0; i < Vec::length(); ++i)
            if (!std::isfinite(v[i])) return false;
    return true;
}

TextureWrap wrapOf(osg::Texture::WrapMode mode)
{
    switch (mode)
    {
    case osg::Texture::REPEAT: return TextureWrap::Repeat;
    case osg::Texture::MIRROR: return TextureWrap::MirroredRepeat;
    default: return TextureWrap::ClampToEdge;
    }
}

TextureFilter filterOf(osg::Texture::FilterMode mode)
{
    switch (mode)
    {
    case osg::Texture::NEAREST: return TextureFilter::Nearest;
    case osg::Texture::LINEAR: return TextureFilter::Linear;
    case osg::Texture::NEAREST_MIPMAP_NEAREST: return TextureFilter::NearestMipmapNearest;
    case osg::Texture::LINEAR_MIPMAP_NEAREST: return TextureFilter::LinearMipmapNearest;
    case osg::Texture::NEAREST_MIPMAP_LINEAR: return TextureFilter::NearestMipmapLinear;
    default: return TextureFilter::LinearMipmapLinear;
    }
}

/** The nearest state set's attribute of a type (unit 0 for textures), or null. */
const osg::StateAttribute* nearestAttribute(const std::vector<const osg::StateSet*>& stateSets,
                                            osg::StateAttribute::Type type, bool texture)
{
    for (const osg::StateSet* stateSet : stateSets)
    {
        if (!stateSet) continue;
        const osg::StateAttribute* attribute =
            texture ? stateSet->getTextureAttribute(0, type) : stateSet->getAttribute(type);
        if (attribute) return attribute;
    }
    return nullptr;
}

/** The nearest state set's setting of a mode, or fallback where none sets it. */
bool nearestMode(const std::vector<const osg::StateSet*>& stateSets, osg::StateAttribute::GLMode mode, bool fallback)
{
    for (const osg::StateSet* stateSet : stateSets)
        if (stateSet && stateSet->getMode(mode) != osg::StateAttribute::INHERIT)
            return (stateSet->getMode(mode) & osg::StateAttribute::ON) != 0;
    return fallback;
}

} // namespace

RiggedPrimitive GeometryConverter::convert(const osg::Geometry& geometry,
                                           const std::vector<const osg::StateSet*>& stateSets, const std::string& place)
{
    RiggedPrimitive primitive;
    primitive.place = place;
    const auto* vertices = dynamic_cast<const osg::Vec3Array*>(geometry.getVertexArray());
    if (!vertices || vertices->empty()) throw Refusal(place, "has no vertices of three floats (osg::Vec3Array)");
    for (const osg::Vec3& v : *vertices) primitive.positions.emplace_back(v.x(), v.y(), v.z());
    if (!allFinite(primitive.positions)) throw Refusal(place, "a vertex is not finite");
    const std::size_t count = primitive.positions.size();

    const auto* normals = dynamic_cast<const osg::Vec3Array*>(geometry.getNormalArray());
    if (normals && normals->size() == count && geometry.getNormalArray()->getBinding() == osg::Array::BIND_PER_VERTEX)
    {
        for (const osg::Vec3& n : *normals) primitive.normals.emplace_back(n.x(), n.y(), n.z());
        if (!allFinite(primitive.normals))
        {
            primitive.normals.clear();
            _warnings.push_back(place + ": a normal is not finite; the normals are left out");
        }
    }
    else if (geometry.getNormalArray())
        _warnings.push_back(place + ": normals that are not one osg::Vec3 per vertex are left out");

    const auto* texCoords = dynamic_cast<const osg::Vec2Array*>(geometry.getTexCoordArray(0));
    if (texCoords && texCoords->size() == count)
    {
        for (const osg::Vec2& t : *texCoords) primitive.texCoords0.emplace_back(t.x(), t.y());
        if (!allFinite(primitive.texCoords0)) primitive.texCoords0.clear();
    }

    osg::TriangleIndexFunctor<TriangleCollector> triangles;
    triangles.indices = &primitive.indices;
    geometry.accept(triangles);
    for (std::size_t i = 0; i < primitive.indices.size(); ++i)
        if (primitive.indices[i] >= count)
            throw Refusal(place, "index " + std::to_string(primitive.indices[i]) + " at position " + std::to_string(i) +
                                     " is out of range (" + std::to_string(count) + " vertices)");
    primitive.material = material(stateSets, place);
    return primitive;
}

int GeometryConverter::material(const std::vector<const osg::StateSet*>& stateSets, const std::string& place)
{
    const osg::StateAttribute* material = nearestAttribute(stateSets, osg::StateAttribute::MATERIAL, false);
    const osg::StateAttribute* texture = nearestAttribute(stateSets, osg::StateAttribute::TEXTURE, true);
    // OSG draws both faces unless face culling is on; blending where it is on.
    const bool culled = nearestMode(stateSets, GL_CULL_FACE, false);
    const bool blended = nearestMode(stateSets, GL_BLEND, false);
    const auto key = std::make_tuple(material, texture, culled, blended);
    const auto known = _materials.find(key);
    if (known != _materials.end()) return known->second;

    RiggedMaterial out;
    if (const auto* source = dynamic_cast<const osg::Material*>(material))
    {
        out.name = source->getName();
        const osg::Vec4& diffuse = source->getDiffuse(osg::Material::FRONT);
        out.baseColorFactor = glm::dvec4(diffuse.r(), diffuse.g(), diffuse.b(), diffuse.a());
    }
    if (const auto* source = dynamic_cast<const osg::Texture*>(texture))
    {
        if (source->getImage(0) && source->getImage(0)->data())
        {
            out.baseColorTexture.image = image(*source->getImage(0), place);
            out.baseColorTexture.wrapS = wrapOf(source->getWrap(osg::Texture::WRAP_S));
            out.baseColorTexture.wrapT = wrapOf(source->getWrap(osg::Texture::WRAP_T));
            out.baseColorTexture.minFilter = filterOf(source->getFilter(osg::Texture::MIN_FILTER));
            out.baseColorTexture.magFilter = filterOf(source->getFilter(osg::Texture::MAG_FILTER));
        }
        else _warnings.push_back(place + ": its texture has no image; it is drawn untextured");
    }
    out.doubleSided = !culled;
    if (blended) out.alphaMode = AlphaMode::Blend;
    _model.materials.push_back(out);
    return _materials[key] = int(_model.materials.size()) - 1;
}

int GeometryConverter::image(const osg::Image& source, const std::string& place)
{
    const auto known = _images.find(&source);
    if (known != _images.end()) return known->second;
    RiggedImage out;
    out.name = source.getName();
    out.uri = source.getFileName();
    out.width = unsigned(source.s());
    out.height = unsigned(source.t());
    if (source.r() > 1) _warnings.push_back(place + ": only the first layer of its 3D texture is used");
    // Rows in the image's order: texture coordinate t = 0 is its first row, as RiggedImage's v = 0.
    out.rgba.reserve(std::size_t(out.width) * out.height * 4);
    for (unsigned t = 0; t < out.height; ++t)
        for (unsigned s = 0; s < out.width; ++s)
        {
            const osg::Vec4 colour = source.getColor(s, t);
            for (int c = 0; c < 4; ++c)
                out.rgba.push_back(std::uint8_t(std::lround(std::clamp(colour[c], 0.0f, 1.0f) * 255.0f)));
        }
    _model.images.push_back(std::move(out));
    return _images[&source] = int(_model.images.size()) - 1;
}

} // namespace osganimation
} // namespace osgActor
