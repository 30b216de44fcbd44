#include "TransformFeedbackCapture"

#include <osg/BufferIndexBinding>
#include <osg/BufferObject>
#include <osg/GLExtensions>
#include <osg/Program>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace osgActor {
namespace test {

namespace {

#ifndef GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN
#define GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN 0x8C88
#endif
#ifndef GL_QUERY_RESULT
#define GL_QUERY_RESULT 0x8866
#endif

unsigned numTriangleIndices(const osg::Geometry& geometry)
{
    unsigned count = 0;
    for (unsigned p = 0; p < geometry.getNumPrimitiveSets(); ++p)
        count += geometry.getPrimitiveSet(p)->getNumIndices();
    return count;
}

} // namespace

void TransformFeedbackCapture::drawImplementation(osg::RenderInfo& renderInfo, const osg::Drawable* drawable) const
{
    const osg::GLExtensions* gl = renderInfo.getState()->get<osg::GLExtensions>();
    const unsigned numVertices = numTriangleIndices(*drawable->asGeometry());
    const GLsizeiptr size = static_cast<GLsizeiptr>(numVertices * sizeof(osg::Vec3f));
    // NaN where nothing is written, and a count of the triangles written: a draw that captured nothing cannot pass
    // for one that did.
    captured.assign(numVertices, osg::Vec3f(std::nanf(""), std::nanf(""), std::nanf("")));
    GLuint buffer = 0;
    GLuint query = 0;
    gl->glGenBuffers(1, &buffer);
    gl->glGenQueries(1, &query);
    gl->glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, buffer);
    gl->glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, size, captured.data(), GL_STREAM_READ);
    gl->glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffer);
    gl->glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, query);
    gl->glBeginTransformFeedback(GL_TRIANGLES);
    drawable->drawImplementation(renderInfo);
    gl->glEndTransformFeedback();
    gl->glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
    GLuint written = 0;
    gl->glGetQueryObjectuiv(query, GL_QUERY_RESULT, &written);
    trianglesWritten = written;
    gl->glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, size, captured.data());
    gl->glDeleteQueries(1, &query);
    gl->glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    gl->glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, 0);
    gl->glDeleteBuffers(1, &buffer);
    ++draws;
}

GpuSkinningCapture::GpuSkinningCapture(osg::Node* root, SkinnedMesh& mesh, SkinningProfile profile)
    : _root(new osg::Group), _mesh(&mesh), _profile(profile), _callback(new TransformFeedbackCapture)
{
    std::string error;
    _renderer = OffscreenRenderer::create(96, 96, error);
    EXPECT_TRUE(_renderer) << error;
    if (!_renderer) return;
    if (profile == SkinningProfile::Core)
    {
        osg::State* state = _renderer->getCamera()->getGraphicsContext()->getState();
        state->setUseVertexAttributeAliasing(true);
        state->setUseModelViewAndProjectionUniforms(true);
    }
    osg::ref_ptr<osg::Program> program = createSkinningProgram(mesh.getProgramKey(profile));

    program->addTransformFeedBackVarying("osgActor_modelPosition");
    program->setTransformFeedBackMode(GL_INTERLEAVED_ATTRIBS);
    _root->getOrCreateStateSet()->setAttribute(program.get(), osg::StateAttribute::OVERRIDE);
    _root->addChild(root);
    mesh.getBindPoseGeometry(profile)->setDrawCallback(_callback.get());
    _renderer->setScene(_root.get());
}

std::vector<osg::Vec3f> GpuSkinningCapture::capture(double t)
{
    _callback->captured.clear();
    _callback->trianglesWritten = 0;
    _renderer->update(t);
    _renderer->frameScene();
    _renderer->draw();
    EXPECT_EQ(3 * _callback->trianglesWritten, _callback->captured.size()) << "transform feedback at t = " << t;
    return _callback->captured;
}

double maxDistanceToCpu(const std::vector<osg::Vec3f>& captured, const SkinnedMesh& mesh, const osg::Vec3Array& cpu)
{
    std::vector<unsigned> indices;
    const osg::Geometry& surface = *mesh.getSurface();
    for (unsigned p = 0; p < surface.getNumPrimitiveSets(); ++p)
        for (unsigned i = 0; i < surface.getPrimitiveSet(p)->getNumIndices(); ++i)
            indices.push_back(surface.getPrimitiveSet(p)->index(i));
    EXPECT_EQ(captured.size(), indices.size());
    double largest = 0.0;
    for (std::size_t i = 0; i < std::min(captured.size(), indices.size()); ++i)
    {
        const double distance = (captured[i] - cpu[indices[i]]).length();
        if (!std::isfinite(distance)) return std::numeric_limits<double>::infinity(); // not captured
        largest = std::max(largest, distance);
    }
    return largest;
}

} // namespace test
} // namespace osgActor
