// osgactorrender: renders any scene osgDB can read into PNG images offscreen, through OSMesa, with no display.
//
//   osgactorrender data/humanoid.actor -o out/frame_%04d.png --frames 0 47 --contact-sheet out/sheet.png
//
// Exit status 0 when every image was written; 1 with a message on stderr otherwise.
#include "ContactSheet.h"
#include "OffscreenRenderer.h"
#include "OutputPattern.h"
#include "ProgressBar.h"
#include "RenderOptions.h"
#include "RetargetPreview.h"
#include "SceneLoader.h"

#include <osg/ArgumentParser>
#include <osg/Notify>
#include <osgDB/FileUtils>
#include <osgDB/WriteFile>

#include <chrono>
#include <iostream>
#include <memory>

using namespace osgActorRender;

namespace {

int fail(const std::string& message)
{
    std::cerr << "osgactorrender: " << message << std::endl;
    return 1;
}

bool writeImage(const osg::Image& image, const std::string& file, std::string& error)
{
    osgDB::makeDirectoryForFile(file);
    if (osgDB::writeImageFile(image, file)) return true;
    error = "cannot write \"" + file + "\" (is the folder writable, and the extension one osgDB writes, e.g. .png?)";
    return false;
}

/** The camera of the first frame: the user's, completed from what the scene draws where the user left it open. */
CameraView chooseCameraView(const RenderOptions& options, const OffscreenRenderer& renderer)
{
    const CameraView framed = renderer.frameScene();
    if (!options.hasEye) return framed;
    CameraView view = options.view;
    if (!options.hasCenter) view.center = framed.center;
    return view;
}

} // namespace

int main(int argc, char** argv)
{
    osg::ArgumentParser arguments(&argc, argv);
    describeRenderOptions(arguments);
    if (arguments.read("-h") || arguments.read("--help"))
    {
        arguments.getApplicationUsage()->write(std::cout, osg::ApplicationUsage::COMMAND_LINE_OPTION);
        return 0;
    }

    RenderOptions options;
    std::string error;
    if (!parseRenderOptions(arguments, options, error)) return fail(error + " (--help lists the options)");
    OutputPattern pattern;
    if (!pattern.parse(options.outputPattern, error)) return fail(error);
    if (options.writeFrames && options.getNumFrames() > 1 && !pattern.hasFrameField())
        return fail("the output \"" + options.outputPattern + "\" has no frame number (%04d) for " +
                    std::to_string(options.getNumFrames()) + " frames");

    osg::ref_ptr<osg::Node> scene = osgActorApps::loadSceneFiles(options.files, error);
    if (scene && !options.retargetPreview.empty())
        scene = osgActorApps::makeRetargetPreview(*scene, options.retargetPreview, error);
    if (!scene) return fail(error);

    std::unique_ptr<OffscreenRenderer> renderer = OffscreenRenderer::create(options.width, options.height, error);
    if (!renderer) return fail("cannot make an offscreen OpenGL context: " + error);
    renderer->setScene(scene.get());
    renderer->setBackground(options.background);
    renderer->setFieldOfView(options.fovyDegrees);

    std::unique_ptr<ContactSheet> sheet;
    if (!options.contactSheet.empty())
        sheet.reset(new ContactSheet(options.getNumFrames(), options.sheetColumns, options.width, options.height,
                                     options.sheetTileWidth, options.background));

    const unsigned numFrames = options.getNumFrames();
    ProgressBar progress(numFrames, numFrames > 1 && (options.forceProgress || ProgressBar::isTerminal(stderr)));
    double renderSeconds = 0.0;
    for (unsigned i = 0; i < numFrames; ++i)
    {
        const auto start = std::chrono::steady_clock::now();
        // Every delta-driven callback sees the frames from 0 up to this one at the frame rate (--time too).
        renderer->stepTo(options.frameTime(i), options.fps);
        if (i == 0) renderer->setCameraView(chooseCameraView(options, *renderer)); // framed once, then fixed
        const osg::ref_ptr<osg::Image> image = renderer->draw();
        renderSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

        if (options.writeFrames && !writeImage(*image, pattern.format(options.frameNumber(i)), error))
        {
            progress.finish();
            return fail(error);
        }
        if (sheet) sheet->addFrame(i, *image);
        progress.step();
    }
    progress.finish();

    if (options.writeFrames)
    {
        std::cout << "osgactorrender: wrote " << pattern.format(options.frameNumber(0));
        if (numFrames > 1) std::cout << " .. " << pattern.format(options.frameNumber(numFrames - 1));
        std::cout << std::endl;
    }
    if (sheet)
    {
        if (!writeImage(*sheet->getImage(), options.contactSheet, error)) return fail(error);
        std::cout << "osgactorrender: wrote contact sheet " << options.contactSheet << std::endl;
    }
    std::cout << "osgactorrender: " << numFrames << " frame(s) of " << options.width << "x" << options.height << ", "
              << 1000.0 * renderSeconds / numFrames << " ms per frame (update, draw, read back)" << std::endl;
    return 0;
}
