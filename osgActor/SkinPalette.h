/* osgActor: one actor's skinning palette for the GPU path of SkinnedMesh, in a uniform array or a texture buffer.
 * Internal to the library. */
#ifndef OSGACTOR_SKINPALETTE_H
#define OSGACTOR_SKINPALETTE_H 1

#include <osgActor/SkinningShaders>
#include <osgActor/core/Span>
#include <osgActor/core/skin/SkinningMatricesJob>

#include <osg/Image>
#include <osg/StateSet>
#include <osg/Uniform>

namespace osgActor {

/** The state set of one palette (one actor, one frame parity) and the floats the shader reads: a uniform array
  * osgActor_palette of vec4s, or an RGBA32F texture buffer on kSkinPaletteTextureUnit; with the skin's bind scale
  * for dual quaternions. */
class SkinPaletteBuffer
{
public:
    /** A palette of numJoints joints of the variant's layout (paletteStride(key) rows each). */
    SkinPaletteBuffer(const SkinningProgramKey& key, unsigned numJoints, double bindScale);

    osg::StateSet* getStateSet() const { return _stateSet.get(); }
    /** The rows, four floats each, that write() fills. */
    float* rows();
    /** Fills the rows (writeSkinPaletteRows()) and marks them for upload at the next draw that applies the state. */
    void write(Span<const glm::mat4> matrices, Span<const glm::mat4> normalMatrices,
               Span<const SkinDualQuaternion> dualQuaternions);

private:
    SkinningProgramKey _key;
    osg::ref_ptr<osg::StateSet> _stateSet;
    osg::ref_ptr<osg::Uniform> _uniform; // UniformArray
    osg::ref_ptr<osg::Image> _image;     // TextureBuffer
};

/** The fields of a variant that fix its palette's layout (method, normals, influences, storage), the others at their
  * defaults: cameras whose programs differ in profile, lights or fragment shaders share one palette. */
SkinningProgramKey paletteLayoutOf(const SkinningProgramKey& key);

/** The rows of a variant's palette (see SkinnedMesh.vert), per skin joint j from row j * paletteStride(key):
  * linear blend, the first three rows of matrices[j] (and, with inverse-transposed normals, of normalMatrices[j]);
  * dual quaternions, the real part then the dual part of dualQuaternions[j], each (x, y, z, w). rows holds
  * 4 * paletteStride(key) floats per joint of the span the method reads. */
void writeSkinPaletteRows(const SkinningProgramKey& key, Span<const glm::mat4> matrices,
                          Span<const glm::mat4> normalMatrices, Span<const SkinDualQuaternion> dualQuaternions,
                          float* rows);

} // namespace osgActor

#endif
