#include "SkinnedMeshDrawState.h"

#include <osg/Program>
#include <osg/StateSet>
#include <osgUtil/StateGraph>


namespace osgActor {

namespace {

constexpr unsigned kMaxLights = 8;
constexpr unsigned kMaxTexGenUnits = 8;

/** A mode or attribute as inherited down the state sets: an outer OVERRIDE holds against inner values that are not
  * PROTECTED (osg::State's rule). */
struct Inherited
{
    unsigned value = osg::StateAttribute::INHERIT;
    const osg::StateAttribute* attribute = nullptr;

    void set(unsigned given, const osg::StateAttribute* givenAttribute = nullptr)
    {
        if ((value & osg::StateAttribute::OVERRIDE) && !(given & osg::StateAttribute::PROTECTED)) return;
        value = given;
        attribute = givenAttribute;
    }
    /** On, or, never set, the default (modes only). */
    bool on(bool byDefault) const
    {
        return value == osg::StateAttribute::INHERIT ? byDefault : (value & osg::StateAttribute::ON) != 0;
    }
};

void inheritMode(const osg::StateSet::ModeList& modes, GLenum mode, Inherited& inherited)
{
    const auto found = modes.find(mode);
    if (found != modes.end()) inherited.set(found->second);
}

/** What the state sets from the root down to a graph turn on. */
struct DrawState
{
    Inherited lighting, lights[kMaxLights], texGen[kMaxTexGenUnits], program;

    /** The graph's parents' state sets first, then its own (no allocation: state graphs are a few levels deep). */
    void inheritDownTo(const osgUtil::StateGraph* graph)
    {
        if (!graph) return;
        inheritDownTo(graph->_parent);
        if (const osg::StateSet* stateSet = graph->getStateSet()) inherit(*stateSet);
    }

    void inherit(const osg::StateSet& stateSet)
    {
        const osg::StateSet::ModeList& modes = stateSet.getModeList();
        inheritMode(modes, GL_LIGHTING, lighting);
        // GL_LIGHT0 .. GL_LIGHT7 are consecutive: one search, then a walk (this runs per actor and camera).
        for (auto mode = modes.lower_bound(GL_LIGHT0); mode != modes.end() && mode->first < GL_LIGHT0 + kMaxLights;
             ++mode)
            lights[mode->first - GL_LIGHT0].set(mode->second);
        const osg::StateSet::TextureModeList& textureModes = stateSet.getTextureModeList();
        for (unsigned unit = 0; unit < kMaxTexGenUnits && unit < textureModes.size(); ++unit)
            inheritMode(textureModes[unit], GL_TEXTURE_GEN_S, texGen[unit]);
        if (const osg::StateSet::RefAttributePair* pair = stateSet.getAttributePair(osg::StateAttribute::PROGRAM))
            program.set(pair->second, pair->first.get());
    }
};

} // namespace

void applyDrawState(const osgUtil::StateGraph* graph, SkinningProgramKey& key)
{
    if (key.profile != SkinningProfile::Compatibility) return;
    DrawState state;
    state.inheritDownTo(graph);
    const Inherited& lighting = state.lighting;

    // A graph that never mentions lighting (no viewer's global state above it) keeps the key's lights.
    if (lighting.value != osg::StateAttribute::INHERIT)
    {
        key.lights = 0;
        if (lighting.on(false))
            for (unsigned i = 0; i < kMaxLights; ++i)
                if (state.lights[i].on(false)) key.lights |= static_cast<std::uint8_t>(1u << i);
    }

    // An attribute's ON/OFF bit means nothing (setAttribute() defaults it to OFF): only its presence counts.
    const osg::Program* inEffect = dynamic_cast<const osg::Program*>(state.program.attribute);
    key.fragmentProgram = inEffect && isFragmentOnlyProgram(*inEffect) ? inEffect : nullptr;
    key.eyeLinearTexGenUnits = 0;
    if (key.fragmentProgram)
        for (unsigned unit = 1; unit < kMaxTexGenUnits; ++unit)
            if (state.texGen[unit].on(false)) key.eyeLinearTexGenUnits |= static_cast<std::uint8_t>(1u << unit);
}

} // namespace osgActor
