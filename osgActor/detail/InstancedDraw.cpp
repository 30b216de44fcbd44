#include <osgActor/detail/InstancedDraw.h>

#include <osg/GLExtensions>
#include <osg/Program>
#include <osg/State>
#include <osg/Uniform>

namespace osgActor {
namespace detail {

namespace {

/** The primitive set issued for count instances, as its own draw() issues it for one: its indices from its element
  * buffer where the geometry draws from buffer objects, from memory otherwise. */
void drawInstanced(osg::State& state, const osg::PrimitiveSet& primitives, bool useBufferObjects, GLsizei count)
{
    const GLenum mode = primitives.getMode();
    switch (primitives.getType())
    {
    case osg::PrimitiveSet::DrawArraysPrimitiveType:
    {
        const osg::DrawArrays& arrays = static_cast<const osg::DrawArrays&>(primitives);
        state.glDrawArraysInstanced(mode, arrays.getFirst(), arrays.getCount(), count);
        return;
    }
    case osg::PrimitiveSet::DrawArrayLengthsPrimitiveType:
    {
        const osg::DrawArrayLengths& lengths = static_cast<const osg::DrawArrayLengths&>(primitives);
        GLint first = lengths.getFirst();
        for (GLsizei length : lengths)
        {
            state.glDrawArraysInstanced(mode, first, length, count);
            first += length;
        }
        return;
    }
    case osg::PrimitiveSet::DrawElementsUBytePrimitiveType:
    case osg::PrimitiveSet::DrawElementsUShortPrimitiveType:
    case osg::PrimitiveSet::DrawElementsUIntPrimitiveType:
    {
        const osg::DrawElements& elements = *primitives.getDrawElements();
        if (elements.getNumIndices() == 0) return;
        const GLenum type = primitives.getType() == osg::PrimitiveSet::DrawElementsUBytePrimitiveType ? GL_UNSIGNED_BYTE
                            : primitives.getType() == osg::PrimitiveSet::DrawElementsUShortPrimitiveType
                                ? GL_UNSIGNED_SHORT
                                : GL_UNSIGNED_INT;
        osg::GLBufferObject* ebo =
            useBufferObjects ? elements.getOrCreateGLBufferObject(state.getContextID()) : nullptr;
        const GLvoid* indices = elements.getDataPointer();
        if (ebo)
        {
            state.getCurrentVertexArrayState()->bindElementBufferObject(ebo);
            indices = reinterpret_cast<const GLvoid*>(ebo->getOffset(elements.getBufferIndex()));
        }
        else
            state.getCurrentVertexArrayState()->unbindElementBufferObject();
        state.glDrawElementsInstanced(mode, static_cast<GLsizei>(elements.getNumIndices()), type, indices, count);
        return;
    }
    default: return; // canDraw() let none other through
    }
}

} // namespace

InstancedDraw::InstancedDraw() : _base(0), _count(0), _texelsPerInstance(4), _bindScale(1.0f)
{
    // Drawn afresh every frame from the geometry's arrays: nothing of its own to compile or cache.
    setUseDisplayList(false);
    setUseVertexBufferObjects(false);
    setUseVertexArrayObject(false);
    setCullingActive(false);
}

bool InstancedDraw::canDraw(const osg::Geometry& geometry)
{
    if (geometry.getDrawCallback() || !geometry.getVertexArray()) return false;
    // A colour per vertex reaches fixed-function lighting through colour material (OSG's viewers turn it on by
    // default), which the program's lighting reads as the one current colour: only a colour for the whole geometry,
    // which drawing its arrays makes current, lights alike.
    const osg::Array* colours = geometry.getColorArray();
    if (colours && colours->getBinding() == osg::Array::BIND_PER_VERTEX && colours->getNumElements() > 1) return false;
    for (unsigned i = 0; i < geometry.getNumPrimitiveSets(); ++i)
    {
        const osg::PrimitiveSet& primitives = *geometry.getPrimitiveSet(i);
        if (primitives.getNumInstances() != 0) return false;
        switch (primitives.getType())
        {
        case osg::PrimitiveSet::DrawArraysPrimitiveType:
        case osg::PrimitiveSet::DrawArrayLengthsPrimitiveType:
        case osg::PrimitiveSet::DrawElementsUBytePrimitiveType:
        case osg::PrimitiveSet::DrawElementsUShortPrimitiveType:
        case osg::PrimitiveSet::DrawElementsUIntPrimitiveType: break;
        default: return false;
        }
    }
    return true;
}

void InstancedDraw::set(const osg::Geometry* geometry, int base, unsigned count, int texelsPerInstance)
{
    _geometry = geometry;
    _base = base;
    _count = count;
    _texelsPerInstance = texelsPerInstance;
}

void InstancedDraw::drawImplementation(osg::RenderInfo& renderInfo) const
{
    if (!_geometry || _count == 0) return;
    osg::State& state = *renderInfo.getState();
    if (_limit) _limit->noteContext(state);
    // The base, the texels per instance and a dual-quaternion skin's bind scale are this draw's alone, not state OSG
    // sorts by: set on the program the state graph applied.
    static const unsigned baseName = osg::Uniform::getNameID("osgActor_instanceBase");
    static const unsigned texelsName = osg::Uniform::getNameID("osgActor_instanceTexels");
    static const unsigned bindScaleName = osg::Uniform::getNameID("osgActor_bindScale");
    if (const osg::Program::PerContextProgram* program = state.getLastAppliedProgramObject())
    {
        const osg::GLExtensions& gl = *state.get<osg::GLExtensions>();
        const GLint base = program->getUniformLocation(baseName);
        if (base >= 0) gl.glUniform1i(base, _base);
        const GLint texels = program->getUniformLocation(texelsName);
        if (texels >= 0) gl.glUniform1i(texels, _texelsPerInstance);
        const GLint bindScale = program->getUniformLocation(bindScaleName);
        if (bindScale >= 0) gl.glUniform1f(bindScale, _bindScale);
    }
    // What osg::Geometry::drawImplementation() does around its primitives, without a vertex array object of its own
    // (one per geometry and context would be the geometry's, which the ordinary path may be using).
    const osg::Geometry& geometry = *_geometry;
    // From buffer objects wherever the GL has them, whether or not the geometry draws from them itself: an instanced
    // draw from client memory is far slower on NVIDIA's drivers (docs/performance.md, "On a GPU"). OSG 3.6 gives a
    // geometry's arrays and element lists their buffer objects either way; one without (taken off by its owner) is
    // read from memory, as osg::Geometry would read it.
    const bool useBufferObjects = state.isVertexBufferObjectSupported();
    osg::VertexArrayState* arrays = state.getCurrentVertexArrayState();
    arrays->setVertexBufferObjectSupported(useBufferObjects);
    // The texture buffer's upload of this frame's instances (osg::TextureBuffer::apply(), as its state set was
    // applied) leaves its buffer bound as an array buffer without telling the vertex array state: client-side arrays
    // would be read from it, and a buffer object the state takes for bound would not be bound again.
    state.get<osg::GLExtensions>()->glBindBuffer(GL_ARRAY_BUFFER_ARB, 0);
    arrays->setCurrentVertexBufferObject(nullptr);
    geometry.drawVertexArraysImplementation(renderInfo);
    const GLsizei count = static_cast<GLsizei>(_count);
    for (unsigned i = 0; i < geometry.getNumPrimitiveSets(); ++i)
        drawInstanced(state, *geometry.getPrimitiveSet(i), useBufferObjects, count);
    if (useBufferObjects)
    {
        arrays->unbindVertexBufferObject();
        arrays->unbindElementBufferObject();
    }
}

} // namespace detail
} // namespace osgActor
