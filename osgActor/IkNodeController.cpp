#include <osgActor/IkNodeController>
#include <osgActor/GlmOsg>

#include <osg/Transform>

namespace osgActor {

namespace {

/** The node's own frame in world space, through its first parent path (the node's own transform included). */
osg::Matrixd worldMatrixOf(osg::Node& node)
{
    const osg::NodePathList paths = node.getParentalNodePaths();
    if (!paths.empty()) return osg::computeLocalToWorld(paths.front());
    osg::NodePath alone(1, &node);
    return osg::computeLocalToWorld(alone);
}

} // namespace

IkNodeController::IkNodeController(IkChainPtr chain, osg::Node* goalNode) : IkController(std::move(chain)),
    _goalNode(goalNode)
{
}

void IkNodeController::update(const ControllerContext& context, ControllerTarget& target)
{
    osg::ref_ptr<osg::Node> goalNode;
    if (_goalNode.lock(goalNode))
    {
        const osg::Matrixd goalWorld = _goalOffset * worldMatrixOf(*goalNode);
        IkGoal goal;
        goal.position = toGlm(goalWorld.getTrans());
        goal.hasOrientation = _followOrientation;
        if (_followOrientation) goal.orientation = toGlm(goalWorld.getRotate());
        osg::ref_ptr<osg::Node> poleNode;
        if (_poleNode.lock(poleNode))
        {
            goal.pole = toGlm(worldMatrixOf(*poleNode).getTrans());
            goal.hasPole = true;
        }
        if (!setGoal(goal, IkGoalSpace::World)) return;
    }
    else if (getGoalSpace() == IkGoalSpace::World && hasGoal())
    {
        clearGoal(); // the node is gone
    }
    IkController::update(context, target);
}

std::shared_ptr<Controller> IkNodeController::cloneController() const
{
    return std::make_shared<IkNodeController>(*this);
}

} // namespace osgActor
