// osgdb_osgactortestclock: a pseudo-loader for the tests of --check-determinism. "scene.osgt.osgactortestclock"
// reads scene.osgt and hangs it below a transform whose update callback reads the wall clock, as a careless
// simulation callback would: the scene then moves differently on every run. Built into the build tree's plugin
// folder for the tests only, never installed.
#include <osg/MatrixTransform>
#include <osg/NodeCallback>
#include <osgDB/FileNameUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>

#include <chrono>

namespace {

/** Slides its transform along X by the microseconds of the steady clock: a different offset every time. */
class WallClockSway : public osg::NodeCallback
{
public:
    void operator()(osg::Node* node, osg::NodeVisitor* visitor) override
    {
        const auto micros = std::chrono::duration_cast<std::chrono::microseconds>(
                                std::chrono::steady_clock::now().time_since_epoch())
                                .count();
        const double offset = double(micros % 1000) / 1000.0; // metres
        static_cast<osg::MatrixTransform*>(node)->setMatrix(osg::Matrix::translate(offset, 0.0, 0.0));
        traverse(node, visitor);
    }
};

class ReaderWriterTestClock : public osgDB::ReaderWriter
{
public:
    ReaderWriterTestClock() { supportsExtension("osgactortestclock", "a scene swaying by the wall clock (tests)"); }

    const char* className() const override { return "osgActor test clock pseudo-loader"; }

    ReadResult readNode(const std::string& file, const osgDB::ReaderWriter::Options* options) const override
    {
        if (!acceptsExtension(osgDB::getLowerCaseFileExtension(file))) return ReadResult::FILE_NOT_HANDLED;
        osg::ref_ptr<osg::Node> scene = osgDB::readRefNodeFile(osgDB::getNameLessExtension(file), options);
        if (!scene) return ReadResult::FILE_NOT_FOUND;
        osg::ref_ptr<osg::MatrixTransform> sway = new osg::MatrixTransform;
        sway->setUpdateCallback(new WallClockSway);
        sway->addChild(scene.get());
        return sway.release();
    }
};

} // namespace

REGISTER_OSGPLUGIN(osgactortestclock, ReaderWriterTestClock)
