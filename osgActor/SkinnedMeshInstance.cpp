#include "SkinnedMeshInstance.h"

#include "SkinnedMeshGeometry.h"

#include <osgActor/core/skin/SkinBinding>
#include <osgActor/core/skin/SkinBoundsJob>
#include <osgActor/core/skin/SkinningJob>

#include <osg/Notify>

namespace osgActor {

namespace {

/** osg::Vec3Array's floats as the core's vectors: both are three packed floats. */
Span<glm::vec3> asGlm(osg::Vec3Array& array)
{
    static_assert(sizeof(osg::Vec3f) == sizeof(glm::vec3), "osg::Vec3f and glm::vec3 are both three floats");
    return Span<glm::vec3>(reinterpret_cast<glm::vec3*>(&array.front()), array.size());
}

} // namespace

osg::BoundingBox toBoundingBox(const SkinBox& box)
{
    if (box.isEmpty()) return osg::BoundingBox();
    return osg::BoundingBox(box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z);
}

SkinnedMeshInstance::SkinnedMeshInstance(ActorNode& actor, const Skin& skin)
    : _actor(&actor), _actorAddress(&actor), _definition(actor.getDefinition()),
      _needsNormalMatrices(skin.getMethod() == SkinningMethod::LinearBlend &&
                           skin.getNormalTransform() == NormalTransform::InverseTranspose),
      _needsDualQuaternions(skin.getMethod() == SkinningMethod::DualQuaternion)
{
    if (!_definition) return;
    SkinBinding binding = bindSkinToDefinition(skin, *_definition);
    if (!binding)
    {
        OSG_WARN << "osgActor: skinned mesh not drawn for actor '" << actor.getName() << "': " << binding.error
                 << std::endl;
        return;
    }
    _definitionJoints = std::move(binding.definitionJoints);
    _matrices.resize(skin.getNumJoints());
    if (_needsNormalMatrices) _normalMatrices.resize(skin.getNumJoints());
    if (_needsDualQuaternions) _dualQuaternions.resize(skin.getNumJoints());
}

bool SkinnedMeshInstance::isBound(const ActorNode& actor) const
{
    return !_definitionJoints.empty() && actor.getDefinition() == _definition;
}

void SkinnedMeshInstance::updateMatrices(const Skin& skin, const ActorPose& pose)
{
    SkinningMatricesJob matricesJob;
    matricesJob.modelMatrices = modelMatricesOf(pose);
    matricesJob.definitionJoints = _definitionJoints;
    matricesJob.inverseBindMatrices = skin.getInverseBindMatrices();
    matricesJob.bindScale = skin.getBindScale();
    matricesJob.matrices = _matrices;
    matricesJob.normalMatrices = _normalMatrices;
    matricesJob.dualQuaternions = _dualQuaternions;
    if (!matricesJob.run()) return; // only on a binding that does not fit the pose, which isBound() rules out

    SkinBox box;
    SkinBoundsJob boundsJob = makeSkinBoundsJob(skin);
    boundsJob.matrices = _matrices;
    boundsJob.bound = &box;
    boundsJob.run();
    _bound = toBoundingBox(box);
    _hasMatrices = true;
    ++statistics.matrixUpdates;
}

void SkinnedMeshInstance::followPose(const ActorNode& actor, unsigned frameNumber)
{
    if (!_followedSkin || !isBound(actor)) return;
    const osg::BoundingBox before = _bound;
    updateMatrices(*_followedSkin, actor.getPose());
    if (!(_bound._min == before._min && _bound._max == before._max)) _boundChanged = true;
    _followed = true;
    _followedFrame = frameNumber;
    _followedRecomputed = actor.getPose().getTotalRecomputedJoints();
}

bool SkinnedMeshInstance::claimFrame(unsigned frame, bool bufferFilled)
{
    // Claims move forward only. A cull of a frame older than the last claimed one comes late: a camera that OSG
    // culls on the draw thread (one added after the viewer's threads started) runs alongside the next frame's update
    // and cull. It takes its frame's buffer as that frame left it; refilling it would do the frame's work twice and
    // put the newer pose in the buffer of the older frame. (Frame numbers compare modulo 2^32.)
    const bool newer = !_culledBefore || static_cast<int>(frame - _lastCullFrame) > 0;
    if (newer)
    {
        _culledBefore = true;
        _lastCullFrame = frame;
        return true;
    }
    // A buffer made this frame (the path or the palette's layout changed) or by a late cull holds nothing yet.
    return !bufferFilled;
}

osg::StateSet* SkinnedMeshInstance::preparePalette(unsigned frame, const SkinningProgramKey& programKey,
                                                   const Skin& skin)
{
    const SkinningProgramKey key = paletteLayoutOf(programKey);
    std::lock_guard<std::mutex> lock(_cullMutex);
    std::unique_ptr<SkinPaletteBuffer>& palette = _palettes[frame % 2];
    const bool keyChanged = key < _paletteKey || _paletteKey < key;
    if (keyChanged)
    {
        // A new layout (the mesh's storage changed, or the first frame): both buffers are remade as they come.
        _palettes[0].reset();
        _palettes[1].reset();
        _paletteKey = key;
    }
    const bool filled = palette != nullptr;
    if (!palette) palette.reset(new SkinPaletteBuffer(key, skin.getNumJoints(), skin.getBindScale()));
    if (claimFrame(frame, filled))
    {
        palette->write(_matrices, _normalMatrices, _dualQuaternions);
        ++statistics.paletteUploads;
    }
    return palette->getStateSet();
}

osg::Geometry* SkinnedMeshInstance::prepareSkinnedGeometry(unsigned frame, const Skin& skin,
                                                           const osg::Geometry& bindPose)
{
    std::lock_guard<std::mutex> lock(_cullMutex);
    const unsigned parity = frame % 2;
    osg::ref_ptr<osg::Geometry>& geometry = _skinnedGeometries[parity];
    const bool filled = geometry.valid();
    if (!geometry)
    {
        geometry = makeSkinnedOutputGeometry(bindPose);
        _skinnedBounds[parity] = new FixedBoundingBox;
        geometry->setComputeBoundingBoxCallback(_skinnedBounds[parity].get());
    }
    if (claimFrame(frame, filled))
    {
        osg::Vec3Array* positions = static_cast<osg::Vec3Array*>(geometry->getVertexArray());
        osg::Vec3Array* normals = static_cast<osg::Vec3Array*>(geometry->getNormalArray());
        skinVertices(skin, *positions, normals);
        positions->dirty();
        if (normals) normals->dirty();
        _skinnedBounds[parity]->box = _bound;
        geometry->dirtyBound();
        geometry->getBoundingBox(); // now, under the lock, rather than lazily in several cull threads
        ++statistics.cpuSkinnings;
    }
    return geometry.get();
}

void SkinnedMeshInstance::skinVertices(const Skin& skin, osg::Vec3Array& positions, osg::Vec3Array* normals) const
{
    SkinningJob job;
    job.method = skin.getMethod();
    job.vertices = skin.getVertices();
    job.matrices = _matrices;
    job.normalMatrices = _normalMatrices;
    job.dualQuaternions = _dualQuaternions;
    job.bindScale = static_cast<float>(skin.getBindScale());
    job.positions = asGlm(positions);
    if (normals && skin.hasNormals()) job.normals = asGlm(*normals);
    job.run();
}

void SkinnedMeshInstance::resizeGLObjectBuffers(unsigned maxSize)
{
    for (unsigned parity = 0; parity < 2; ++parity)
    {
        if (_palettes[parity]) _palettes[parity]->getStateSet()->resizeGLObjectBuffers(maxSize);
        if (_skinnedGeometries[parity]) _skinnedGeometries[parity]->resizeGLObjectBuffers(maxSize);
    }
}

void SkinnedMeshInstance::releaseGLObjects(osg::State* state) const
{
    for (unsigned parity = 0; parity < 2; ++parity)
    {
        if (_palettes[parity]) _palettes[parity]->getStateSet()->releaseGLObjects(state);
        if (_skinnedGeometries[parity]) _skinnedGeometries[parity]->releaseGLObjects(state);
    }
}

} // namespace osgActor
