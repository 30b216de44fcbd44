// The smallest osgActor program: define an arm in code, attach geometry, pose it, print where its joints are.
#include <osgActor/ActorNode>
#include <osgActor/core/ActorDefinitionBuilder>

#include <osg/ShapeDrawable>
#include <osgUtil/UpdateVisitor>

#include <cstdio>

int main()
{
    using namespace osgActor;

    // 1. The definition: joints, offsets (metres) and active DOFs, shared by every instance.
    ActorDefinitionBuilder builder("arm");
    builder.addJoint("r_shoulder").offset(0, 0, 1.4).dofs(kRotationDofs);
    builder.addJoint("r_elbow", "r_shoulder").offset(0, 0, -0.3).dofs(dofBit(Dof::RX))
        .limits(Dof::RX, 0.0, osg::DegreesToRadians(150.0));
    builder.addJoint("r_wrist", "r_elbow").offset(0, 0, -0.25).dofs(Dof::RX | Dof::RZ);
    const BuildResult result = builder.build();
    if (!result)
    {
        std::fprintf(stderr, "%s\n", result.error.c_str());
        return 1;
    }

    // 2. An instance, with a forearm hung below the elbow as an ordinary OSG child.
    osg::ref_ptr<ActorNode> actor = new ActorNode(result.definition);
    osg::ref_ptr<osg::Geode> forearm = new osg::Geode;
    forearm->addDrawable(new osg::ShapeDrawable(new osg::Capsule(osg::Vec3(0, 0, -0.125f), 0.04f, 0.17f)));
    actor->getSkeletonNode("r_elbow")->addChild(forearm.get());

    // 3. Pose it by name: raise the arm forward and bend the elbow.
    actor->setDof("r_shoulder.rx", osg::DegreesToRadians(-90.0));
    actor->setDof("r_elbow.rx", osg::DegreesToRadians(90.0));
    actor->setPreTranslation(osg::Vec3d(0, 0, 0));

    // 4. One update traversal (a viewer does this every frame), then ask where the joints are.
    osgUtil::UpdateVisitor update;
    actor->accept(update);
    std::printf("%-12s %8s %8s %8s\n", "joint", "x", "y", "z");
    for (unsigned j = 0; j < actor->getNumSkeletonNodes(); ++j)
    {
        const osg::Vec3d p = actor->getJointWorldPosition(j);
        std::printf("%-12s %8.3f %8.3f %8.3f\n", actor->getSkeletonNode(j)->getName().c_str(), p.x(), p.y(), p.z());
    }
    return 0;
}
