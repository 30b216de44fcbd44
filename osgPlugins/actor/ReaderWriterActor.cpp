/* osgdb_actor: the osgDB plugin for .actor files (docs/actor-format.md), and the mocap pseudo-loader
 * ("walk.bvh.actor", docs/mocap.md). */
#include "MocapPseudoLoader"
#include "RiggedModelPseudoLoader"

#include <osgActor/ActorSceneIO>
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>

#include <osg/NodeVisitor>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/Registry>
#include <osgDB/fstream>

namespace {

/** Collects the actors of a scene (not those nested in actors: they belong to their attached geometry). */
class FindActors : public osg::NodeVisitor
{
public:
    FindActors() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    void apply(osg::Transform& node) override
    {
        if (osgActor::ActorNode* actor = dynamic_cast<osgActor::ActorNode*>(&node)) actors.push_back(actor);
        else traverse(node);
    }
    std::vector<const osgActor::ActorNode*> actors;
};

/** Reads and writes one actor per .actor file. Stateless, so several threads may use it at once. */
class ReaderWriterActor : public osgDB::ReaderWriter
{
public:
    ReaderWriterActor()
    {
        supportsExtension("actor", "osgActor actor (definition, pose and geometry)");
        supportsOption("amc=<file>", "walk.asf.actor: the AMC motion of the ASF skeleton (else one found beside it)");
        supportsOption("scale=<s>", "walk.bvh.actor / .asf.actor: file units to model units");
        supportsOption("up=<Y|Z>", "walk.bvh.actor / .asf.actor: the file's up axis (Y by default)");
        supportsOption("fps=<n>", "walk.asf.actor: AMC frame rate (120 by default)");
        supportsOption("dropFirstFrame", "walk.bvh.actor: drop the reference pose in frame 0");
        supportsOption("rootMotion=<skeleton|transforms|inplace>", "mocap pseudo-loader: where the root's travel goes");
        supportsOption("clip=<name>", "hero.glb.actor / .gltf.actor: the animation to play (else the first)");
        supportsOption("rootScale=<above|lengths>", "hero.glb.actor: the root's scale above the actor or in its lengths");
    }

    const char* className() const override { return "osgActor .actor reader/writer"; }

    // osgconv and others ask for an object: an actor is one.
    ReadResult readObject(const std::string& file, const Options* options) const override
    {
        return readNode(file, options);
    }

    ReadResult readObject(std::istream& in, const Options* options) const override { return readNode(in, options); }

    WriteResult writeObject(const osg::Object& object, const std::string& file, const Options* options) const override
    {
        const osg::Node* node = dynamic_cast<const osg::Node*>(&object);
        return node ? writeNode(*node, file, options) : WriteResult(WriteResult::FILE_NOT_HANDLED);
    }

    ReadResult readNode(const std::string& file, const Options* options) const override
    {
        const std::string extension = osgDB::getLowerCaseFileExtension(file);
        if (!acceptsExtension(extension)) return ReadResult::FILE_NOT_HANDLED;
        // Pseudo-loaders ("walk.bvh.actor") dispatch on the inner extension; plain files are .actor.
        if (osgActorPlugin::isMocapPseudoFile(file)) return osgActorPlugin::readMocapPseudoFile(file, options);
        if (osgActorPlugin::isRiggedModelPseudoFile(file)) return osgActorPlugin::readRiggedModelPseudoFile(file, options);
        return readActorFile(file, options);
    }

    ReadResult readNode(std::istream& in, const Options* options) const override
    {
        return readActorStream(in, "<stream>", options);
    }

    WriteResult writeNode(const osg::Node& node, const std::string& file, const Options* options) const override
    {
        if (!acceptsExtension(osgDB::getLowerCaseFileExtension(file))) return WriteResult::FILE_NOT_HANDLED;
        osgDB::ofstream out(file.c_str());
        if (!out) return WriteResult("cannot open " + file + " for writing");
        WriteResult result = writeNode(node, out, options);
        out.close();
        if (result.success() && out.fail()) return WriteResult("cannot write " + file);
        return result;
    }

    WriteResult writeNode(const osg::Node& node, std::ostream& out, const Options*) const override
    {
        FindActors finder;
        const_cast<osg::Node&>(node).accept(finder); // the visitor only reads
        if (finder.actors.size() != 1)
            return WriteResult("a .actor file holds exactly one actor; the scene has " +
                               std::to_string(finder.actors.size()));
        osgActor::writeActor(out, osgActor::extractActorDocument(*finder.actors.front()));
        return out.fail() ? WriteResult("cannot write the actor") : WriteResult(WriteResult::FILE_SAVED);
    }

private:
    /** A .actor file on disk, found on the data file path of the options. */
    ReadResult readActorFile(const std::string& file, const Options* options) const
    {
        const std::string path = osgDB::findDataFile(file, options);
        if (path.empty()) return ReadResult::FILE_NOT_FOUND;
        osgDB::ifstream in(path.c_str());
        if (!in) return ReadResult("cannot open " + path);
        return readActorStream(in, path, options);
    }

    /** Parses, validates and builds; fileName is for messages and for finding models next to the file. */
    ReadResult readActorStream(std::istream& in, const std::string& fileName, const Options* options) const
    {
        const osgActor::ActorReadResult read = osgActor::readActor(in, fileName);
        if (!read) return ReadResult(read.error);
        const osgActor::ActorNodeResult built =
            osgActor::createActorNode(read.document, read.definition, fileName, options);
        if (!built.actor) return ReadResult(built.error);
        return ReadResult(built.actor.get());
    }
};

} // namespace

REGISTER_OSGPLUGIN(actor, ReaderWriterActor)
