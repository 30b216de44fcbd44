// osgactorshowcase: writes the showcase scene (data/showcase.osgt), which osgviewer, osgactorviewer and
// osgactorrender load like any other scene once libosgActorShowcase and the osgActor plugins are on
// OSG_LIBRARY_PATH.
//
//   osgactorshowcase data/showcase.osgt
#include "ShowcaseScene.h"

#include <osg/ArgumentParser>
#include <osgDB/WriteFile>

#include <iostream>

int main(int argc, char** argv)
{
    osg::ArgumentParser arguments(&argc, argv);
    osg::ApplicationUsage* usage = arguments.getApplicationUsage();
    usage->setApplicationName(arguments.getApplicationName());
    usage->setDescription(arguments.getApplicationName() + " writes the osgActor showcase scene.");
    usage->setCommandLineUsage(arguments.getApplicationName() + " [options] output.osgt");
    usage->addCommandLineOption("--walker <file>", "The actor walking round the dancer, as osgDB reads it, relative "
                                                   "to the output's folder (default: Cesium Man, data/models).");
    usage->addCommandLineOption("--walker-speed <m/s>", "Its speed along its path (default: Cesium Man's).");
    usage->addCommandLineOption("--dancer <file>", "The motion-capture dancer, as osgDB reads it, relative to the "
                                                   "output's folder (default: the CMU Charleston in data/mocap).");
    usage->addCommandLineOption("--no-dancer", "Leave the dancer (and Cesium Man dancing its motion) out.");
    usage->addCommandLineOption("--dancer-scale <s>", "Scale from the dancer file's units to metres (default CMU's).");
    usage->addCommandLineOption("--dancer-y-up", "The dancer file is Y up (turned to Z up).");
    if (arguments.read("-h") || arguments.read("--help"))
    {
        usage->write(std::cout, osg::ApplicationUsage::COMMAND_LINE_OPTION);
        return 0;
    }

    osgActorShowcase::ShowcaseSources sources;
    while (arguments.read("--walker", sources.walker)) {}
    while (arguments.read("--walker-speed", sources.walkerSpeed)) {}
    while (arguments.read("--dancer", sources.dancer)) {}
    while (arguments.read("--no-dancer")) sources.dancer.clear();
    while (arguments.read("--dancer-scale", sources.dancerScale)) {}
    while (arguments.read("--dancer-y-up")) sources.dancerYUp = true;
    arguments.reportRemainingOptionsAsUnrecognized();
    if (arguments.errors())
    {
        arguments.writeErrorMessages(std::cerr);
        return 1;
    }
    if (arguments.argc() != 2 || arguments.isOption(1))
    {
        std::cerr << "osgactorshowcase: give one output file (--help lists the options)" << std::endl;
        return 1;
    }

    const std::string output = arguments[1];
    const osg::ref_ptr<osg::Group> scene = osgActorShowcase::makeShowcaseScene(sources);
    if (!osgDB::writeNodeFile(*scene, output))
    {
        std::cerr << "osgactorshowcase: cannot write \"" << output << "\"" << std::endl;
        return 1;
    }
    std::cout << "osgactorshowcase: wrote " << output << std::endl;
    return 0;
}
