// Loads an .actor file through osgDB, as any OSG program would, with the osgActor plugins osgDB finds (the installed
// ones, through OSG_LIBRARY_PATH or a prefix osgDB searches), writes it back as .actor and reads that again.
//   load_actor IN.actor OUT.actor
// Prints the plugin osgDB loaded and the actor's size; exits 1, saying why, if anything is not as expected.
#include <osgActor/ActorNode>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgDB/WriteFile>

#include <cmath>
#include <cstdio>
#include <string>

namespace {

osg::ref_ptr<osgActor::ActorNode> readActor(const char* path)
{
    osg::ref_ptr<osg::Node> node = osgDB::readRefNodeFile(path);
    osg::ref_ptr<osgActor::ActorNode> actor = dynamic_cast<osgActor::ActorNode*>(node.get());
    if (!actor) std::fprintf(stderr, "load_actor: %s gave no osgActor::ActorNode\n", path);
    return actor;
}

} // namespace

int main(int argc, char** argv)
{
    if (argc != 3)
    {
        std::fprintf(stderr, "usage: load_actor IN.actor OUT.actor\n");
        return 1;
    }
    osgDB::Registry* registry = osgDB::Registry::instance();
    const std::string plugin = osgDB::findLibraryFile(registry->createLibraryNameForExtension("actor"));
    std::printf("plugin %s\n", plugin.c_str());

    osg::ref_ptr<osgActor::ActorNode> actor = readActor(argv[1]);
    if (!actor) return 1;
    // A pose to keep: the first joint turned by half a radian about its Z axis.
    const std::string dof = actor->getSkeletonNode(0u)->getName() + ".rz";
    if (!actor->setDof(dof, 0.5)) return 1;
    if (!osgDB::writeNodeFile(*actor, argv[2]))
    {
        std::fprintf(stderr, "load_actor: cannot write %s\n", argv[2]);
        return 1;
    }
    osg::ref_ptr<osgActor::ActorNode> back = readActor(argv[2]);
    if (!back) return 1;
    double turned = 0.0;
    if (back->getNumSkeletonNodes() != actor->getNumSkeletonNodes() || back->getNumDofs() != actor->getNumDofs() ||
        !back->getDof(dof, turned) || std::abs(turned - 0.5) > 1e-9)
    {
        std::fprintf(stderr, "load_actor: %s does not read back as it was written\n", argv[2]);
        return 1;
    }
    std::printf("actor %s: %u joints, %u DOFs, read, written and read back\n", actor->getName().c_str(),
                actor->getNumSkeletonNodes(), actor->getNumDofs());
    return 0;
}
