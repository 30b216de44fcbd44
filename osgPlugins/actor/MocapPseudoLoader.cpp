#include "MocapPseudoLoader"

#include <osgActor/MocapActor>

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>

namespace osgActorPlugin {

bool isMocapPseudoFile(const std::string& file)
{
    if (osgDB::getLowerCaseFileExtension(file) != "actor") return false;
    const std::string inner = osgDB::getLowerCaseFileExtension(osgDB::getNameLessExtension(file));
    return inner == "bvh" || inner == "asf";
}

osgDB::ReaderWriter::ReadResult readMocapPseudoFile(const std::string& file, const osgDB::Options* options)
{
    using ReadResult = osgDB::ReaderWriter::ReadResult;
    const std::string inner = osgDB::getNameLessExtension(file);
    const std::string path = osgDB::findDataFile(inner, options);
    if (path.empty()) return ReadResult(ReadResult::FILE_NOT_FOUND);

    osgActor::MocapActorOptions mocap;
    std::string error;
    if (options && !osgActor::parseMocapOptionString(options->getOptionString(), mocap, error))
        return ReadResult(file + ": " + error);
    if (!mocap.amcFile.empty())
    {
        // An AMC named in the options: beside the ASF first, then wherever the data path finds it.
        const std::string beside = osgDB::concatPaths(osgDB::getFilePath(path), mocap.amcFile);
        const std::string found = osgDB::fileExists(beside) ? beside : osgDB::findDataFile(mocap.amcFile, options);
        if (found.empty()) return ReadResult(file + ": cannot find the AMC file '" + mocap.amcFile + "'");
        mocap.amcFile = found;
    }
    osg::ref_ptr<osgActor::ActorNode> actor = osgActor::readMocapActor(path, mocap, error);
    if (!actor) return ReadResult(error);
    return ReadResult(actor.get());
}

} // namespace osgActorPlugin
