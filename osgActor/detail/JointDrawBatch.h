// Internal to the library (not installed, NOT API): drawables of one actor that share a state graph, drawn as one
// render leaf (ActorCull). OSG's render graph costs a render leaf per drawable per frame (pooled, but each one
// referenced, linked into its state graph and reset again), most of a crowd's cull once the traversal itself is
// gone; the actor's drawables in one state graph of a bin sorted by state are drawn one after the other anyway,
// so one leaf draws them all, each with its own model-view matrix, as consecutive leaves would.
#ifndef OSGACTOR_DETAIL_JOINTDRAWBATCH_H
#define OSGACTOR_DETAIL_JOINTDRAWBATCH_H 1

#include <osg/Drawable>
#include <osg/Matrixd>

#include <vector>

namespace osgActor {
namespace detail {

class JointDrawBatch : public osg::Drawable
{
public:
    JointDrawBatch();

    /** A batch from this thread's pool, empty: one whose render leaf the cull visitor has let go of (it holds it
      * until it culls again with the same render stage, after that stage was drawn), else a new one. */
    static JointDrawBatch* acquire();

    /** depth: the drawable's as the cull visitor computes it (tests compare it; a bin sorted by state ignores it). */
    void add(osg::Drawable& drawable, const osg::Matrixd& modelView, float depth)
    {
        _entries.push_back({&drawable, modelView, depth});
    }
    unsigned getNumEntries() const { return static_cast<unsigned>(_entries.size()); }
    const osg::Drawable* getEntryDrawable(unsigned i) const { return _entries[i].drawable.get(); }
    const osg::Matrixd& getEntryModelView(unsigned i) const { return _entries[i].modelView; }
    float getEntryDepth(unsigned i) const { return _entries[i].depth; }

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
    struct Entry
    {
        osg::ref_ptr<osg::Drawable> drawable; // kept alive until drawn, as a render leaf keeps its drawable
        osg::Matrixd modelView;
        float depth;
    };
    std::vector<Entry> _entries;
};

} // namespace detail
} // namespace osgActor

#endif
