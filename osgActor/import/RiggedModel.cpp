#include <osgActor/import/RiggedModel>

#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace osgActor {

glm::dmat4 restMatrix(const RiggedNode& node)
{
    glm::dmat4 m = glm::mat4_cast(node.rotation);
    m[0] *= node.scale.x;
    m[1] *= node.scale.y;
    m[2] *= node.scale.z;
    m[3] = glm::dvec4(node.translation, 1.0);
    return m;
}

glm::dmat4 restSceneMatrix(const RiggedModel& model, int node)
{
    glm::dmat4 m(1.0);
    for (int n = node; n >= 0; n = model.nodes[n].parent) m = restMatrix(model.nodes[n]) * m;
    return m;
}

bool isSelfOrAncestor(const RiggedModel& model, int ancestor, int node)
{
    for (int n = node; n >= 0; n = model.nodes[n].parent)
        if (n == ancestor) return true;
    return false;
}

} // namespace osgActor
