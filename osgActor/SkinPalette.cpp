#include "SkinPalette.h"

#include <osg/TextureBuffer>

namespace osgActor {

namespace {

/** Row r of a 4x4 matrix (GLM stores columns): its entries in columns 0..3. */
void writeRow(const glm::mat4& m, unsigned r, float* out)
{
    out[0] = m[0][r];
    out[1] = m[1][r];
    out[2] = m[2][r];
    out[3] = m[3][r];
}

void writeQuaternion(const glm::quat& q, float* out)
{
    out[0] = q.x;
    out[1] = q.y;
    out[2] = q.z;
    out[3] = q.w;
}

} // namespace

SkinningProgramKey paletteLayoutOf(const SkinningProgramKey& key)
{
    SkinningProgramKey layout;
    layout.skinning = key.skinning;
    layout.method = key.method;
    layout.inverseTranspose = key.inverseTranspose;
    layout.influences = key.influences;
    layout.palette = key.palette;
    return layout;
}

void writeSkinPaletteRows(const SkinningProgramKey& key, Span<const glm::mat4> matrices,
                          Span<const glm::mat4> normalMatrices, Span<const SkinDualQuaternion> dualQuaternions,
                          float* rows)
{
    const unsigned stride = paletteStride(key);
    if (key.method == SkinningMethod::DualQuaternion)
    {
        for (std::size_t j = 0; j < dualQuaternions.size(); ++j)
        {
            float* out = rows + 4 * stride * j;
            writeQuaternion(dualQuaternions[j].real, out);
            writeQuaternion(dualQuaternions[j].dual, out + 4);
        }
        return;
    }
    for (std::size_t j = 0; j < matrices.size(); ++j)
    {
        float* out = rows + 4 * stride * j;
        for (unsigned r = 0; r < 3; ++r) writeRow(matrices[j], r, out + 4 * r);
        if (key.inverseTranspose)
            for (unsigned r = 0; r < 3; ++r) writeRow(normalMatrices[j], r, out + 4 * (3 + r));
    }
}

SkinPaletteBuffer::SkinPaletteBuffer(const SkinningProgramKey& key, unsigned numJoints, double bindScale)
    : _key(key), _stateSet(new osg::StateSet)
{
    const unsigned numRows = numJoints * paletteStride(key);
    if (key.palette == SkinPaletteStorage::TextureBuffer)
    {
        _image = new osg::Image;
        _image->allocateImage(static_cast<int>(numRows), 1, 1, GL_RGBA, GL_FLOAT);
        _image->setInternalTextureFormat(GL_RGBA32F_ARB);
        osg::ref_ptr<osg::TextureBuffer> buffer = new osg::TextureBuffer(_image.get());
        buffer->setInternalFormat(GL_RGBA32F_ARB);
        _stateSet->setTextureAttribute(kSkinPaletteTextureUnit, buffer.get());
    }
    else
    {
        _uniform = new osg::Uniform(osg::Uniform::FLOAT_VEC4, "osgActor_palette", static_cast<int>(numRows));
        _stateSet->addUniform(_uniform.get());
    }
    if (key.method == SkinningMethod::DualQuaternion)
        _stateSet->addUniform(new osg::Uniform("osgActor_bindScale", static_cast<float>(bindScale)));
}

float* SkinPaletteBuffer::rows()
{
    if (_image) return reinterpret_cast<float*>(_image->data());
    return &_uniform->getFloatArray()->front();
}

void SkinPaletteBuffer::write(Span<const glm::mat4> matrices, Span<const glm::mat4> normalMatrices,
                              Span<const SkinDualQuaternion> dualQuaternions)
{
    writeSkinPaletteRows(_key, matrices, normalMatrices, dualQuaternions, rows());
    if (_image) _image->dirty();
    else _uniform->dirty();
}

} // namespace osgActor
