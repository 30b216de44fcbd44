#include <osgActor/RiggedGeometry>

#include <osg/BlendFunc>
#include <osg/CullFace>
#include <osg/Image>
#include <osg/Material>
#include <osg/Texture2D>
#include <osg/Uniform>

namespace osgActor {

namespace {

osg::Texture::WrapMode wrapOf(TextureWrap wrap)
{
    switch (wrap)
    {
    case TextureWrap::ClampToEdge: return osg::Texture::CLAMP_TO_EDGE;
    case TextureWrap::MirroredRepeat: return osg::Texture::MIRROR;
    default: return osg::Texture::REPEAT;
    }
}

osg::Texture::FilterMode filterOf(TextureFilter filter)
{
    switch (filter)
    {
    case TextureFilter::Nearest: return osg::Texture::NEAREST;
    case TextureFilter::Linear: return osg::Texture::LINEAR;
    case TextureFilter::NearestMipmapNearest: return osg::Texture::NEAREST_MIPMAP_NEAREST;
    case TextureFilter::LinearMipmapNearest: return osg::Texture::LINEAR_MIPMAP_NEAREST;
    case TextureFilter::NearestMipmapLinear: return osg::Texture::NEAREST_MIPMAP_LINEAR;
    default: return osg::Texture::LINEAR_MIPMAP_LINEAR;
    }
}

osg::ref_ptr<osg::Texture2D> createTexture(const RiggedImage& source, const RiggedTexture& settings)
{
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(int(source.width), int(source.height), 1, GL_RGBA, GL_UNSIGNED_BYTE);
    std::copy(source.rgba.begin(), source.rgba.end(), image->data());
    image->setInternalTextureFormat(GL_RGBA8);
    image->setFileName(source.uri);
    osg::ref_ptr<osg::Texture2D> texture = new osg::Texture2D(image.get());
    texture->setWrap(osg::Texture::WRAP_S, wrapOf(settings.wrapS));
    texture->setWrap(osg::Texture::WRAP_T, wrapOf(settings.wrapT));
    texture->setFilter(osg::Texture::MIN_FILTER, filterOf(settings.minFilter));
    texture->setFilter(osg::Texture::MAG_FILTER, filterOf(settings.magFilter));
    return texture;
}

} // namespace

osg::ref_ptr<osg::StateSet> createMaterialStateSet(const RiggedModel& model, int materialIndex)
{
    const RiggedMaterial material = materialIndex >= 0 ? model.materials[materialIndex] : RiggedMaterial();
    osg::ref_ptr<osg::StateSet> state = new osg::StateSet;
    osg::ref_ptr<osg::Material> colour = new osg::Material;
    const glm::dvec4& c = material.baseColorFactor;
    const osg::Vec4 base(float(c.r), float(c.g), float(c.b), float(c.a));
    colour->setDiffuse(osg::Material::FRONT_AND_BACK, base);
    colour->setAmbient(osg::Material::FRONT_AND_BACK, base);
    state->setAttributeAndModes(colour.get());
    // The same material for osgActor's programs (SkinningShaders), which in the core profile have no built-in one.
    state->addUniform(new osg::Uniform("osgActor_baseColor", base));
    const int image = material.baseColorTexture.image;
    const bool textured = image >= 0 && !model.images[image].rgba.empty();
    if (textured)
        state->setTextureAttributeAndModes(0, createTexture(model.images[image], material.baseColorTexture).get());
    state->addUniform(new osg::Uniform("osgActor_hasBaseColorTexture", textured));
    state->addUniform(new osg::Uniform("osgActor_baseColorTexture", 0));
    if (material.alphaMode == AlphaMode::Blend)
    {
        state->setAttributeAndModes(new osg::BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA));
        state->setRenderingHint(osg::StateSet::TRANSPARENT_BIN);
    }
    if (!material.doubleSided) state->setAttributeAndModes(new osg::CullFace(osg::CullFace::BACK));
    return state;
}

osg::ref_ptr<osg::Geometry> createPrimitiveSurface(const RiggedModel& model, const RiggedPrimitive& primitive)
{
    osg::ref_ptr<osg::Geometry> geometry = new osg::Geometry;
    geometry->setName(primitive.place);
    const unsigned set = primitive.material >= 0 ? model.materials[primitive.material].baseColorTexture.texCoord : 0;
    const std::vector<glm::vec2>& uv = set == 1 ? primitive.texCoords1 : primitive.texCoords0;
    if (!uv.empty())
    {
        osg::ref_ptr<osg::Vec2Array> coordinates = new osg::Vec2Array;
        for (const glm::vec2& t : uv) coordinates->push_back(osg::Vec2(t.x, t.y));
        geometry->setTexCoordArray(0, coordinates.get(), osg::Array::BIND_PER_VERTEX);
    }
    osg::ref_ptr<osg::DrawElementsUInt> triangles =
        new osg::DrawElementsUInt(GL_TRIANGLES, primitive.indices.begin(), primitive.indices.end());
    geometry->addPrimitiveSet(triangles.get());
    return geometry;
}

osg::ref_ptr<osg::Geometry> createPrimitiveGeometry(const RiggedModel& model, const RiggedPrimitive& primitive)
{
    osg::ref_ptr<osg::Geometry> geometry = createPrimitiveSurface(model, primitive);
    osg::ref_ptr<osg::Vec3Array> positions = new osg::Vec3Array;
    for (const glm::vec3& p : primitive.positions) positions->push_back(osg::Vec3(p.x, p.y, p.z));
    geometry->setVertexArray(positions.get());
    if (!primitive.normals.empty())
    {
        osg::ref_ptr<osg::Vec3Array> normals = new osg::Vec3Array;
        for (const glm::vec3& n : primitive.normals) normals->push_back(osg::Vec3(n.x, n.y, n.z));
        geometry->setNormalArray(normals.get(), osg::Array::BIND_PER_VERTEX);
    }
    geometry->setUseVertexBufferObjects(true);
    return geometry;
}

osg::ref_ptr<SkinnedMesh> createSkinnedMesh(const RiggedModel& model, const SkinnedPrimitive& skinned)
{
    const RiggedPrimitive& primitive = model.meshes[skinned.mesh].primitives[skinned.primitive];
    osg::ref_ptr<SkinnedMesh> mesh = new SkinnedMesh(skinned.skin, createPrimitiveSurface(model, primitive).get());
    mesh->setName(primitive.place);
    return mesh;
}

} // namespace osgActor
