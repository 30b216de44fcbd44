// Internal to the library (not installed, NOT API): drawables of one actor that share a state graph, drawn as one
// render leaf (ActorCull). OSG's render graph costs a render leaf per drawable per frame (pooled, but each one
// referenced, linked into its state graph and reset again), most of a crowd's cull once the traversal itself is
// gone; the actor's drawables in one state graph of a bin sorted by state are drawn one after the other anyway,
// so one leaf draws them all, each with its joint's model-view matrix, as consecutive leaves would.
#ifndef OSGACTOR_DETAIL_JOINTDRAWBATCH_H
#define OSGACTOR_DETAIL_JOINTDRAWBATCH_H 1

#include <osg/Drawable>
#include <osg/Matrixd>
#include <osgUtil/CullVisitor>

#include <vector>

namespace osgActor {
namespace detail {

/** A point's depth in front of the eye, as the cull visitor computes it for the render graph's depth sorting (its
  * own function is private to it): minus the eye-space z. Inline: the instanced cull asks it of every instance. */
inline float eyeDepth(const osg::Vec3& point, const osg::Matrixd& modelView)
{
    using Value = osgUtil::CullVisitor::value_type;
    return static_cast<float>(-(static_cast<Value>(point[0]) * modelView(0, 2) +
                                static_cast<Value>(point[1]) * modelView(1, 2) +
                                static_cast<Value>(point[2]) * modelView(2, 2) + modelView(3, 2)));
}

/** The eye-space frames of one actor for one cull: the actor's own (index 0) and each planned joint's (index
  * joint + 1), OSG's row-vector order. Shared by the batches that draw with them, and written only while nothing
  * else holds them (the cull asks referenceCount()), so a frame still being drawn keeps its matrices. */
class JointModelViews : public osg::Referenced
{
public:
    std::vector<osg::Matrixd> matrices;

protected:
    ~JointModelViews() override = default;
};

class JointDrawBatch : public osg::Drawable
{
public:
    JointDrawBatch();

    /** Empties the batch for the given matrices; keepAlive holds the drawables it will be given (the actor's cull
      * plan), as a render leaf keeps its drawable until drawn. */
    void reset(const osg::Referenced* keepAlive, const JointModelViews* modelViews);
    /** A drawable and the index of its frame in the matrices. */
    struct Entry
    {
        const osg::Drawable* drawable;
        unsigned frame;
    };
    void add(const osg::Drawable& drawable, unsigned frame) { _entries.push_back({&drawable, frame}); }
    /** Adds entries (as another batch holds them). */
    void add(const Entry* first, std::size_t count) { _entries.insert(_entries.end(), first, first + count); }
    const std::vector<Entry>& getEntries() const { return _entries; }

    unsigned getNumEntries() const { return static_cast<unsigned>(_entries.size()); }
    const osg::Drawable* getEntryDrawable(unsigned i) const { return _entries[i].drawable; }
    const osg::Matrixd& getEntryModelView(unsigned i) const { return _modelViews->matrices[_entries[i].frame]; }
    /** The drawable's depth as the cull visitor computes it (tests compare it; a bin sorted by state ignores it). */
    float getEntryDepth(unsigned i) const
    {
        return eyeDepth(_entries[i].drawable->getBoundingBox().center(), getEntryModelView(i));
    }

    /** Each drawable with its model-view matrix, as RenderLeaf::render() draws consecutive leaves of one state
      * graph: the matrix applied (and OSG's matrix uniforms where the state uses them), then the drawable. */
    void drawImplementation(osg::RenderInfo& renderInfo) const override;

    const char* libraryName() const override { return "osgActor"; }
    const char* className() const override { return "JointDrawBatch"; }
    osg::Object* cloneType() const override { return new JointDrawBatch; }
    osg::Object* clone(const osg::CopyOp&) const override { return new JointDrawBatch; }

protected:
    ~JointDrawBatch() override = default;

private:
    std::vector<Entry> _entries;
    osg::ref_ptr<const osg::Referenced> _keepAlive;
    osg::ref_ptr<const JointModelViews> _modelViews;
};

} // namespace detail
} // namespace osgActor

#endif
