#include "RiggedModelPseudoLoader"

#include <osgActor/RiggedModelActor>
#include <osgActor/import/RiggedModelFile>

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>

namespace osgActorPlugin {

bool isRiggedModelPseudoFile(const std::string& file)
{
    return osgDB::getLowerCaseFileExtension(file) == "actor" &&
           osgActor::isRiggedModelFile(osgDB::getNameLessExtension(file));
}

osgDB::ReaderWriter::ReadResult readRiggedModelPseudoFile(const std::string& file, const osgDB::Options* options)
{
    using ReadResult = osgDB::ReaderWriter::ReadResult;
    const std::string path = osgDB::findDataFile(osgDB::getNameLessExtension(file), options);
    if (path.empty()) return ReadResult(ReadResult::FILE_NOT_FOUND);
    osgActor::RiggedModelActorOptions rigged;
    std::string error;
    if (options && !osgActor::parseRiggedModelOptionString(options->getOptionString(), rigged, error))
        return ReadResult(file + ": " + error);
    const osgActor::RiggedModelActor read = osgActor::readRiggedModelActor(path, rigged, error);
    if (!read.actor) return ReadResult(error);
    return ReadResult(read.sceneNode.get());
}

} // namespace osgActorPlugin
