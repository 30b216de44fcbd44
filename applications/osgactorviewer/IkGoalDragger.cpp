#include "IkGoalDragger.h"

#include <osg/Geode>
#include <osg/Material>
#include <osg/ShapeDrawable>

namespace osgActorViewer {

namespace {

/** The actor's own chain ending at the joint, or a DLS chain from two joints up. */
osgActor::IkChainPtr chainEndingAt(const osgActor::ActorNode& actor, unsigned joint, std::string& error)
{
    const osgActor::ActorDefinition& definition = *actor.getDefinition();
    for (const osgActor::IkChainPtr& chain : actor.getIkChains())
        if (chain->getSpec().effectorJoint == definition.getJointName(joint)) return chain;

    int root = int(joint);
    for (int up = 0; up < 2 && definition.getParent(unsigned(root)) != osgActor::kNoParent; ++up)
        root = definition.getParent(unsigned(root));
    if (root == int(joint))
    {
        error = definition.getJointName(joint) + " is a root joint: no chain ends there";
        return nullptr;
    }
    osgActor::IkChainSpec spec;
    spec.name = "viewer goal";
    spec.rootJoint = definition.getJointName(unsigned(root));
    spec.effectorJoint = definition.getJointName(joint);
    spec.solver = osgActor::IkSolverType::Dls;
    const osgActor::IkChainBuildResult built = osgActor::buildIkChain(definition, spec);
    if (!built) error = built.error;
    return built.chain;
}

osg::ref_ptr<osg::Geode> makeMarker(float radius)
{
    osg::ref_ptr<osg::Geode> marker = new osg::Geode;
    marker->addDrawable(new osg::ShapeDrawable(new osg::Sphere(osg::Vec3(), radius)));
    osg::ref_ptr<osg::Material> material = new osg::Material;
    material->setDiffuse(osg::Material::FRONT_AND_BACK, osg::Vec4(1.0f, 0.85f, 0.1f, 1.0f));
    material->setEmission(osg::Material::FRONT_AND_BACK, osg::Vec4(0.4f, 0.3f, 0.0f, 1.0f));
    marker->getOrCreateStateSet()->setAttributeAndModes(material.get());
    return marker;
}

} // namespace

IkGoalDragger::IkGoalDragger(osg::Group* parent) : _parent(parent) {}

IkGoalDragger::~IkGoalDragger() { detach(); }

std::string IkGoalDragger::attach(osgActor::ActorNode& actor, unsigned joint)
{
    detach();
    if (!actor.getDefinition() || joint >= actor.getNumSkeletonNodes()) return "no joint to put a goal on";
    std::string error;
    const osgActor::IkChainPtr chain = chainEndingAt(actor, joint, error);
    if (!chain) return "no IK chain: " + error;

    // The goal starts where the effector is, so nothing jumps until the user drags.
    const osg::Vec3d start = actor.getJointWorldPosition(joint);
    const float size = std::max(0.05f, 0.12f * actor.getBound().radius());
    _goal = new osg::MatrixTransform(osg::Matrixd::translate(start));
    _goal->addChild(makeMarker(0.15f * size).get());
    _dragger = new osgManipulator::TranslateAxisDragger;
    _dragger->setupDefaultGeometry();
    _dragger->setMatrix(osg::Matrixd::scale(size, size, size) * osg::Matrixd::translate(start));
    _dragger->addTransformUpdating(_goal.get());
    _dragger->setHandleEvents(true);
    _handle = new osg::Group;
    _handle->setName("IK goal");
    _handle->addChild(_goal.get());
    _handle->addChild(_dragger.get());
    _parent->addChild(_handle.get());

    _controller = std::make_shared<osgActor::IkNodeController>(chain, _goal.get());
    actor.addController(_controller);
    _actor = &actor;
    return "drag the arrows: chain " + chain->getSpec().rootJoint + " .. " + chain->getSpec().effectorJoint +
           " follows (g again to let go)";
}

void IkGoalDragger::detach()
{
    osg::ref_ptr<osgActor::ActorNode> actor;
    if (_controller && _actor.lock(actor)) actor->removeController(_controller);
    _controller.reset();
    _actor = nullptr;
    if (_handle && _parent) _parent->removeChild(_handle.get());
    _handle = nullptr;
    _goal = nullptr;
    _dragger = nullptr;
}

} // namespace osgActorViewer
