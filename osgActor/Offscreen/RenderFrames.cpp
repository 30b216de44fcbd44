#include <osgActor/Offscreen/RenderFrames>

#include <osgActor/Offscreen/OffscreenRenderer>

#include "SceneLoader.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace osgActor {

namespace {

// OSMesa's largest viewport (SWRAST_MAX_WIDTH/HEIGHT in Mesa); larger buffers would only waste memory.
const int kMaxImageSize = 16384;
// The most update steps from time 0 to the last frame (about 9 hours of simulation at 30 frames per second).
const double kMaxSteps = 1e6;

bool validateTimes(const std::vector<double>& times, const RenderSettings& settings, std::string& error)
{
    if (times.empty())
    {
        error = "no time to render";
        return false;
    }
    for (size_t i = 0; i < times.size(); ++i)
    {
        if (!std::isfinite(times[i]) || times[i] < 0.0)
            error = "time " + std::to_string(times[i]) + " s is not a finite time from 0 on";
        else if (i > 0 && times[i] < times[i - 1])
            error = "the times must not go back (" + std::to_string(times[i]) + " s after " +
                    std::to_string(times[i - 1]) + " s): players do not rewind";
        if (!error.empty()) return false;
    }
    if (settings.framingTime >= 0.0 && settings.framingTime > times.front())
    {
        error = "the framing time comes after the first time rendered";
        return false;
    }
    if (times.back() * settings.fps > kMaxSteps)
    {
        error = "the scene is updated at every frame from time 0: more than " + std::to_string(long(kMaxSteps)) +
                " frames (time x fps) is too many";
        return false;
    }
    return true;
}

/** The settings' camera, completed from what the scene draws where the settings leave it open. */
void placeCamera(OffscreenRenderer& renderer, const RenderSettings& settings)
{
    osg::Vec3d eye, center, up;
    renderer.computeFramingView(eye, center, up);
    if (settings.hasEye)
    {
        eye = settings.eye;
        up = settings.up;
        if (settings.hasCenter) center = settings.center;
    }
    renderer.setViewMatrixAsLookAt(eye, center, up);
}

/** FNV-1a over the pixels, row by row (rows may be padded). */
std::uint64_t hashPixels(const osg::Image& image)
{
    std::uint64_t hash = 14695981039346656037ull;
    const unsigned rowBytes = image.getRowSizeInBytes();
    for (int y = 0; y < image.t(); ++y)
    {
        const unsigned char* row = image.data(0, y);
        for (unsigned i = 0; i < rowBytes; ++i) hash = (hash ^ row[i]) * 1099511628211ull;
    }
    return hash;
}

} // namespace

bool RenderSettings::validate(std::string& error) const
{
    if (width < 1 || height < 1 || width > kMaxImageSize || height > kMaxImageSize)
        error = "the image size must be from 1 to " + std::to_string(kMaxImageSize) + " pixels each way";
    else if (!(fps > 0.0) || !std::isfinite(fps)) error = "the frame rate must be a positive number";
    else if (!(fovyDegrees > 0.0 && fovyDegrees < 180.0)) error = "the field of view must lie in (0, 180) degrees";
    else if (up.length2() == 0.0) error = "the up direction cannot be the zero vector";
    else if (hasEye && hasCenter && eye == center) error = "the eye and the centre cannot be the same point";
    else if (!std::isfinite(framingTime)) error = "the framing time must be a number";
    return error.empty();
}

bool renderFrames(osg::Node* scene, const std::vector<double>& times, const RenderSettings& settings,
                  const FrameCallback& onFrame, std::string& error)
{
    if (scene == nullptr)
    {
        error = "no scene to render";
        return false;
    }
    if (!settings.validate(error) || !validateTimes(times, settings, error)) return false;
    osg::ref_ptr<OffscreenRenderer> renderer = OffscreenRenderer::create(settings.width, settings.height, error);
    if (!renderer)
    {
        error = "cannot make an offscreen OpenGL context: " + error;
        return false;
    }

    std::srand(settings.seed);
    if (settings.playAnimations) playOsgAnimations(*scene);
    renderer->setScene(scene);
    renderer->setBackground(settings.background);
    renderer->setFieldOfView(settings.fovyDegrees);

    // Framed once, at the pose of the framing time, then fixed.
    renderer->stepTo(settings.framingTime >= 0.0 ? settings.framingTime : times.front(), settings.fps);
    placeCamera(*renderer, settings);
    for (size_t i = 0; i < times.size(); ++i)
    {
        renderer->stepTo(times[i], settings.fps);
        const osg::ref_ptr<osg::Image> image = renderer->draw();
        if (onFrame && !onFrame(unsigned(i), *image)) break;
    }
    return true;
}

bool renderFrames(osg::Node* scene, const std::vector<double>& times, const RenderSettings& settings,
                  std::vector<osg::ref_ptr<osg::Image>>& images, std::string& error)
{
    images.clear();
    return renderFrames(scene, times, settings,
                        [&images](unsigned, osg::Image& image) {
                            images.push_back(&image);
                            return true;
                        },
                        error);
}

osg::ref_ptr<osg::Node> readScene(const std::vector<std::string>& files, std::string& error)
{
    return osgActorApps::loadSceneFiles(files, error);
}

bool renderFile(const std::string& file, const std::vector<double>& times, const RenderSettings& settings,
                std::vector<osg::ref_ptr<osg::Image>>& images, std::string& error)
{
    std::srand(settings.seed);
    const osg::ref_ptr<osg::Node> scene = readScene({file}, error);
    return scene && renderFrames(scene.get(), times, settings, images, error);
}

DeterminismCheck checkDeterminism(const SceneFactory& makeScene, const std::vector<double>& times,
                                  const RenderSettings& settings, const std::function<void()>& onFrame)
{
    DeterminismCheck result;
    std::vector<std::uint64_t> firstRun;
    for (int run = 0; run < 2 && result.firstDifferingFrame < 0; ++run)
    {
        std::srand(settings.seed);
        const osg::ref_ptr<osg::Node> scene = makeScene(result.error);
        if (!scene) return result;
        const bool rendered = renderFrames(
            scene.get(), times, settings,
            [&](unsigned index, osg::Image& image) {
                const std::uint64_t hash = hashPixels(image);
                if (run == 0) firstRun.push_back(hash);
                else if (hash != firstRun[index]) result.firstDifferingFrame = int(index);
                if (onFrame) onFrame();
                return result.firstDifferingFrame < 0;
            },
            result.error);
        if (!rendered) return result;
    }
    result.completed = true;
    return result;
}

} // namespace osgActor
