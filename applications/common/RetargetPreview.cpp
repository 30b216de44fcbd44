#include "RetargetPreview.h"

#include <osgActor/ActorRetarget>
#include <osgActor/GlmOsg>
#include <osgActor/MocapActor>
#include <osgActor/core/ActorPose>
#include <osgActor/core/ClipPlayer>

#include <glm/geometric.hpp>

#include <osg/Group>
#include <osg/MatrixTransform>
#include <osg/NodeVisitor>

namespace osgActorApps {

namespace {

/** The first ActorNode below a node, hidden parts included. */
class FirstActor : public osg::NodeVisitor
{
public:
    FirstActor() : osg::NodeVisitor(osg::NodeVisitor::TRAVERSE_ALL_CHILDREN)
    {
        setTraversalMask(~0u);
        setNodeMaskOverride(~0u);
    }
    void apply(osg::Transform& transform) override
    {
        if (!actor) actor = dynamic_cast<osgActor::ActorNode*>(&transform);
        if (!actor) traverse(transform);
    }
    osgActor::ActorNode* actor = nullptr;
};

/** A unit vector across the way the source's root travels over the clip, in the target's model frame (+X when it
  * stays put). */
osg::Vec3d besideTravel(const osgActor::ActorNode& source, const osgActor::Clip& motion,
                        const osgActor::RetargetRig& rig)
{
    if (rig.getSourceRoot() < 0 || !motion.isUniform() || motion.getNumFrames() < 2) return osg::Vec3d(1, 0, 0);
    osgActor::ActorPose pose(source.getDefinition());
    auto rootAt = [&](unsigned frame) {
        pose.setDofs(motion.getFrame(frame), motion.getNumChannels());
        pose.updateMatrices();
        return glm::dvec3(pose.getModelMatrix(static_cast<unsigned>(rig.getSourceRoot()))[3]);
    };
    glm::dvec3 travel = rig.getAlignment() * (rootAt(motion.getNumFrames() - 1) - rootAt(0));
    travel.z = 0.0;
    if (glm::length(travel) < 0.5 * rig.getSourceHipHeight()) return osg::Vec3d(1, 0, 0);
    const glm::dvec3 across = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), travel));
    return osgActor::toOsg(across);
}

} // namespace

osg::ref_ptr<osg::Node> makeRetargetPreview(osg::Node& scene, const std::string& motionFile, std::string& error)
{
    FirstActor finder;
    scene.accept(finder);
    osgActor::ActorNode* target = finder.actor;
    if (!target)
    {
        error = "--retarget-preview: the scene has no actor to retarget onto";
        return nullptr;
    }
    const osg::ref_ptr<osgActor::ActorNode> source =
        osgActor::readMocapActor(motionFile, osgActor::MocapActorOptions(), error);
    if (!source) return nullptr;
    const osgActor::ClipLibraryPtr& library = source->getClipLibrary();
    const osgActor::ClipPtr motion =
        library && library->getNumClips() ? library->getClip(library->getClipNames().front()) : osgActor::ClipPtr();
    if (!motion)
    {
        error = motionFile + ": no motion to retarget";
        return nullptr;
    }

    // The motion retargeted onto the actor, which plays nothing else.
    osgActor::RetargetSkeleton from, onto;
    from.definition = source->getDefinition();
    onto.definition = target->getDefinition();
    onto.map = osgActor::getActorJointMap(*target);
    const osgActor::RetargetRigBuildResult rig = osgActor::buildRetargetRig(from, onto);
    if (!rig)
    {
        error = "--retarget-preview: " + rig.error;
        return nullptr;
    }
    osgActor::RetargetClipOptions options;
    options.ik = true;
    options.name = motion->getName() + " retargeted";
    const osgActor::RetargetClipResult retargeted = osgActor::retargetClip(*rig.rig, *motion, options);
    if (!retargeted)
    {
        error = "--retarget-preview: " + retargeted.error;
        return nullptr;
    }
    if (!target->getClipLibrary()) target->setClipLibrary(std::make_shared<osgActor::ClipLibrary>());
    target->getClipLibrary()->addClip(retargeted.clip);
    const std::vector<osgActor::ControllerPtr> controllers = target->getControllers();
    for (const osgActor::ControllerPtr& controller : controllers)
        if (std::dynamic_pointer_cast<osgActor::ClipPlayer>(controller)) target->removeController(controller);
    auto player = std::make_shared<osgActor::ClipPlayer>(retargeted.clip);
    player->setName("retargeted");
    player->setPlayMode(osgActor::PlayMode::Loop);
    player->play();
    target->addController(player);

    // The source beside it, in the actor's frame: scaled and turned as the retargeting maps its positions, then moved
    // a body's width and a half to the side of the way the motion travels (so the two walk abreast, not in file).
    const osg::Vec3d aside = besideTravel(*source, *motion, *rig.rig) * (1.2 * rig.rig->getTargetHipHeight());
    const osg::Matrixd place = osg::Matrixd::scale(osg::Vec3d(1, 1, 1) * rig.rig->getScale()) *
                               osgActor::toOsg(glm::dmat4(rig.rig->getAlignment())) * osg::Matrixd::translate(aside) *
                               target->getMatrix();
    osg::ref_ptr<osg::MatrixTransform> beside = new osg::MatrixTransform(place);
    beside->getOrCreateStateSet()->setMode(GL_RESCALE_NORMAL, osg::StateAttribute::ON);
    beside->addChild(source.get());
    osg::ref_ptr<osg::Group> group = new osg::Group;
    group->addChild(&scene);
    group->addChild(beside.get());
    return group;
}

} // namespace osgActorApps
