/* osgActor: what one actor owns of a SkinnedMesh: its binding, matrices, bound and double-buffered outputs. Internal
 * to the library. */
#ifndef OSGACTOR_SKINNEDMESHINSTANCE_H
#define OSGACTOR_SKINNEDMESHINSTANCE_H 1

#include "SkinPalette.h"

#include <osgActor/ActorNode>
#include <osgActor/SkinnedMesh>
#include <osgActor/core/skin/SkinningMatricesJob>
#include <osgActor/detail/PoseFollower.h>

#include <osg/Geometry>
#include <osg/observer_ptr>

#include <memory>
#include <mutex>
#include <vector>

namespace osgActor {

/** A box an osg::Geometry reports as its own without looking at its vertices. */
class FixedBoundingBox : public osg::Drawable::ComputeBoundingBoxCallback
{
public:
    osg::BoundingBox box;
    osg::BoundingBox computeBound(const osg::Drawable&) const override { return box; }
};

/** One actor's state in a SkinnedMesh. The update traversal writes the matrices and the bound (or, for an actor in
  * an ActorGroup, the actor's worker right after the actor's update: followPose()); the cull traversal reads them
  * (OSG never overlaps the two) and fills this frame's buffer under a mutex, once per frame whatever the number of
  * cameras; the draw of the previous frame may still read the other buffer meanwhile. */
class SkinnedMeshInstance : public detail::PoseFollower
{
public:
    /** Binds the skin to the actor's definition; isBound() says whether it could. */
    SkinnedMeshInstance(ActorNode& actor, const Skin& skin);

    bool isOf(const ActorNode& actor) const { return _actorAddress == &actor && _actor.valid(); }
    bool isAlive() const { return _actor.valid(); }
    /** The actor, or null once it is gone. */
    const ActorNode* getActor() const { return _actor.get(); }
    /** Whether this state was made for that definition (bound to it or not). */
    bool isFor(const ActorDefinitionPtr& definition) const { return _definition == definition; }
    /** Whether the actor's definition has every joint of the skin, and is still the one bound. */
    bool isBound(const ActorNode& actor) const;

    /** The skinning matrices (and the normal matrices or dual quaternions the skin's method needs) and the bound,
      * from the pose's model matrices, which the caller has brought up to date. */
    void updateMatrices(const Skin& skin, const ActorPose& pose);
    bool hasMatrices() const { return _hasMatrices; }

    /** The skin followPose() skins with (the mesh's): set when the update traversal lists the instance. */
    void setFollowedSkin(const SkinPtr& skin)
    {
        if (_followedSkin != skin) _followedSkin = skin;
    }
    /** updateMatrices() from the actor's pose on the actor's worker (the model matrices are current), noting the
      * frame and a change of the bound. */
    void followPose(const ActorNode& actor, unsigned frameNumber) override;
    /** Whether followPose() did this frame's work at the pose the actor has now. */
    bool hasFollowed(unsigned frameNumber, const ActorPose& pose) const
    {
        return _followed && _followedFrame == frameNumber && !pose.hasDirtyJoints() &&
               pose.getTotalRecomputedJoints() == _followedRecomputed;
    }
    /** Whether followPose() changed the bound since the last call (the mesh's bound must then be dirtied, on the
      * update thread); clears it. */
    bool takeBoundChange()
    {
        const bool changed = _boundChanged;
        _boundChanged = false;
        return changed;
    }
    /** Model space, as of the last updateMatrices(). */
    const osg::BoundingBox& getBound() const { return _bound; }

    /** The palette rows of a program variant (writeSkinPaletteRows()) from the current matrices, at rows. */
    void writePaletteRows(const SkinningProgramKey& key, float* rows) const
    {
        writeSkinPaletteRows(paletteLayoutOf(key), _matrices, _normalMatrices, _dualQuaternions, rows);
    }
    /** This frame's palette state set, filled from the matrices the first time a frame asks. */
    osg::StateSet* preparePalette(unsigned frame, const SkinningProgramKey& key, const Skin& skin);
    /** This frame's skinned geometry, skinned on the CPU the first time a frame asks. */
    osg::Geometry* prepareSkinnedGeometry(unsigned frame, const Skin& skin, const osg::Geometry& bindPose);

    /** CPU skinning of the whole skin from the current matrices into arrays of the skin's size (file order). */
    void skinVertices(const Skin& skin, osg::Vec3Array& positions, osg::Vec3Array* normals) const;

    bool hasOwnPath = false;
    SkinnedMesh::SkinningPath ownPath = SkinnedMesh::GPU_SKINNING;
    SkinnedMesh::Statistics statistics;

    void resizeGLObjectBuffers(unsigned maxSize);
    void releaseGLObjects(osg::State* state) const;

private:
    /** Whether this frame's work is still to do, claiming it: the first cull of a frame newer than any claimed yet,
      * or a cull whose buffer holds nothing yet (bufferFilled false). Call with _cullMutex held. */
    bool claimFrame(unsigned frame, bool bufferFilled);

    osg::observer_ptr<ActorNode> _actor;
    const ActorNode* _actorAddress;
    ActorDefinitionPtr _definition;
    std::vector<std::uint32_t> _definitionJoints; // empty when not bound
    bool _needsNormalMatrices;
    bool _needsDualQuaternions;

    std::vector<glm::mat4> _matrices;
    std::vector<glm::mat4> _normalMatrices;
    std::vector<SkinDualQuaternion> _dualQuaternions;
    bool _hasMatrices = false;
    osg::BoundingBox _bound;

    // followPose(): on the actor's worker; read by the update thread after.
    SkinPtr _followedSkin;
    bool _followed = false;
    bool _boundChanged = false;
    unsigned _followedFrame = 0;
    std::uint64_t _followedRecomputed = 0; // the pose's getTotalRecomputedJoints() then

    std::mutex _cullMutex;
    bool _culledBefore = false;
    unsigned _lastCullFrame = 0;
    // By frame parity.
    std::unique_ptr<SkinPaletteBuffer> _palettes[2];
    SkinningProgramKey _paletteKey;
    osg::ref_ptr<osg::Geometry> _skinnedGeometries[2];
    osg::ref_ptr<FixedBoundingBox> _skinnedBounds[2];
};

/** The box's corners as an osg::BoundingBox (invalid for an empty box). */
osg::BoundingBox toBoundingBox(const SkinBox& box);

} // namespace osgActor

#endif
