// The whole frame drawn, side by side in one run (issues 26 and 28): N rigid humanoids (osgActor, osgAnimation,
// plain OSG; the benchmark's 31-joint humanoid with a box under every joint) and N skinned Cesium Men (osgActor's
// SkinnedMesh on its GPU path, drawn one by one or instanced; osgAnimation's RigGeometry with
// RigTransformHardware; the _group and _threaded systems update and prepare their cull on an ActorGroup's thread
// per core, the _threaded ones instanced), standing on a square grid that
// the camera frames, animated, drawn at 1280 x 720 through osgViewer into a headless context: on a GPU through EGL
// (osgactor_gpu_draw_bench, EglPbufferContext: no X server needed), or on OSMesa (osgactor_osmesa_draw_bench,
// OsMesaGraphicsContext). Each frame ends with glFinish, so its time holds the GL's work too. Reported per system and
// N: milliseconds per frame and frames per second, the update, cull and draw-dispatch times and (EGL) the GPU's draw
// time from OSG's own statistics, and the ratio to the peers at the same N.
//
//   osgactor_gpu_draw_bench [--actors=1000,10000] [--systems=NAME,...] [--seconds=S] [--size=WxH]
//                           [--threading=single|draw] [--small-features=cull|draw] [--device=I] [--images=DIR]
//                           [--cesium-man=FILE]
//
// --small-features=draw turns OSG's small-feature culling off: from a camera that frames 10,000 rigid humanoids, their
// 12 cm boxes are under a pixel and every system culls them all by default, so only then is their draw measured.
// With --images, each run's last frame is written to DIR/<system>_<N>.png, and the skinned Cesium Man is drawn once
// on the GPU path and once on the CPU path at the same time of its clip, both written, and compared (the GPU's vertex
// shader against the CPU's skinning job, on real hardware). Not part of the test suite.
#if OSGACTOR_DRAW_BENCH_OSMESA
#include "OsMesaGraphicsContext"
using HeadlessContext = bench::OsMesaGraphicsContext;
#else
#include "EglPbufferContext"
using HeadlessContext = bench::EglPbufferContext;
#endif

#include "../actors/CountList"
#include "../actors/PeerScenes"
#include "../skin_draw/SkinnedCrowds"

#include <osgActor/ActorGroup>
#include <osgActor/ActorNode>

#include <osg/ComputeBoundsVisitor>
#include <osg/Image>
#include <osg/MatrixTransform>
#include <osg/ShapeDrawable>
#include <osg/Stats>
#include <osg/Timer>
#include <osgDB/FileUtils>
#include <osgDB/WriteFile>
#include <osgViewer/Viewer>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

struct Options
{
    std::vector<int> actors{1000, 10000};
    std::vector<std::string> systems{"rigid_osgActor",
                                     "rigid_osgActor_group",
                                     "rigid_osgActor_instanced",
                                     "rigid_osgActor_instanced_threaded",
                                     "rigid_osgAnimation",
                                     "rigid_plainOSG",
                                     "skinned_osgActor_gpu",
                                     "skinned_osgActor_instanced",
                                     "skinned_osgActor_instanced_threaded",
                                     "skinned_osgAnimation_hw"};
    double seconds = 3.0;
    int width = 1280, height = 720;
    bool drawThread = false;
    bool smallFeatureCulling = true; // OSG's default: drawables under a few pixels are culled

    int device = -1;
    std::string imageDir;
    std::string cesiumMan = std::string(OSGACTOR_BENCH_DATA_DIR) + "/models/CesiumMan/CesiumMan.gltf";
};

/** The ActorGroup a crowd holds below a chain of single children (the skinned group crowds put the file's root
  * transform above it), or null; toCrowd: the group's frame to the crowd's. */
osgActor::ActorGroup* findActorGroup(osg::Group& crowd, osg::Matrixd& toCrowd)
{
    toCrowd.makeIdentity();
    osg::NodePath path;
    for (osg::Group* node = &crowd; node; node = node->getNumChildren() == 1 ? node->getChild(0)->asGroup() : nullptr)
    {
        path.push_back(node);
        if (osgActor::ActorGroup* group = dynamic_cast<osgActor::ActorGroup*>(node))
        {
            toCrowd = osg::computeLocalToWorld(path);
            return group;
        }
    }
    return nullptr;
}

/** Puts the crowd's members on a square grid (spacing in metres, world space): under a transform each, or, for an
  * ActorGroup whose members must stay its children, through each actor's pre-translation (in the group's frame). */
void placeOnGrid(osg::Group& crowd, double spacing)
{
    osg::Matrixd groupToCrowd;
    osgActor::ActorGroup* group = findActorGroup(crowd, groupToCrowd);
    const osg::Matrixd crowdToGroup = osg::Matrixd::inverse(groupToCrowd);
    const unsigned n = group ? group->getNumChildren() : crowd.getNumChildren();
    const unsigned side = static_cast<unsigned>(std::ceil(std::sqrt(double(n))));
    for (unsigned i = 0; i < n; ++i)
    {
        const osg::Vec3d position((i % side) * spacing, (i / side) * spacing, 0.0);
        if (group)
        {
            // Where the actor's frame is the group's, moved by the pre-translation: the grid's point in that frame,
            // less the origin's (the translation is a difference of points).
            const osg::Vec3d moved = position * crowdToGroup - osg::Vec3d() * crowdToGroup;
            static_cast<osgActor::ActorNode*>(group->getChild(i))->setPreTranslation(moved);
            continue;
        }
        osg::ref_ptr<osg::MatrixTransform> place = new osg::MatrixTransform(osg::Matrixd::translate(position));
        place->addChild(crowd.getChild(i));
        crowd.setChild(i, place.get());
    }
}

/** The threads of the _group and _threaded systems' ActorGroups: one per core. */
unsigned allCores() { return std::max(1u, std::thread::hardware_concurrency()); }

osg::ref_ptr<osg::Group> makeCrowd(const std::string& system, unsigned n, const Options& options)
{
    osg::ref_ptr<osg::Group> crowd;
    if (system == "rigid_osgActor") crowd = bench::makeOsgActorScene(n, bench::OsgActorCrowd());
    else if (system == "rigid_osgActor_group")
    {
        bench::OsgActorCrowd group;
        group.threads = allCores();
        crowd = bench::makeOsgActorScene(n, group);
    }
    else if (system == "rigid_osgActor_instanced" || system == "rigid_osgActor_instanced_threaded")
    {
        bench::OsgActorCrowd instanced;
        instanced.instanced = true;
        if (system == "rigid_osgActor_instanced_threaded") instanced.threads = allCores();
        crowd = bench::makeOsgActorScene(n, instanced);
    }
    else if (system == "rigid_osgAnimation") crowd = bench::makeOsgAnimationScene(n);
    else if (system == "rigid_plainOSG") crowd = bench::makePlainOsgScene(n);
    else if (system == "skinned_osgActor_gpu")
        crowd = bench::makeSkinnedCrowd(bench::SkinnedSystem::OsgActorGpu, n, options.cesiumMan);
    else if (system == "skinned_osgActor_instanced")
        crowd = bench::makeSkinnedCrowd(bench::SkinnedSystem::OsgActorGpuInstanced, n, options.cesiumMan);
    else if (system == "skinned_osgActor_instanced_threaded")
        crowd = bench::makeSkinnedCrowd(bench::SkinnedSystem::OsgActorGpuInstanced, n, options.cesiumMan, allCores());
    else if (system == "skinned_osgActor_cpu")
        crowd = bench::makeSkinnedCrowd(bench::SkinnedSystem::OsgActorCpu, n, options.cesiumMan);
    else if (system == "skinned_osgAnimation_hw")
        crowd = bench::makeSkinnedCrowd(bench::SkinnedSystem::OsgAnimationHardware, n, options.cesiumMan);
    else if (system == "skinned_osgAnimation_sw")
        crowd = bench::makeSkinnedCrowd(bench::SkinnedSystem::OsgAnimationSoftware, n, options.cesiumMan);
    if (crowd) placeOnGrid(*crowd, 1.2);
    return crowd;
}

/** Ends every frame with glFinish, so that a frame's time holds its GPU work; reads the pixels back when asked. */
struct FinishAndRead : osg::Camera::DrawCallback
{
    void operator()(osg::RenderInfo& renderInfo) const override
    {
        if (read)
        {
            const osg::Viewport* viewport = renderInfo.getCurrentCamera()->getViewport();
            image = new osg::Image;
            image->readPixels(0, 0, int(viewport->width()), int(viewport->height()), GL_RGB, GL_UNSIGNED_BYTE);
            read = false;
        }
        glFinish();
    }
    mutable bool read = false;
    mutable osg::ref_ptr<osg::Image> image;
};

/** Prints each distinct OSG message once: osgAnimation repeats one notice per hardware rig sharing a shader
  * ("MAX_MATRIX not found"), which would bury the table at 10,000 characters. */
class OncePerMessage : public osg::NotifyHandler
{
public:
    void notify(osg::NotifySeverity, const char* message) override
    {
        std::lock_guard<std::mutex> lock(_mutex);
        if (_seen.insert(message).second) std::fputs(message, stderr);
    }

private:
    std::mutex _mutex;
    std::set<std::string> _seen;
};

/** What the driver calls itself: GL_VENDOR, GL_RENDERER and GL_VERSION (while a context is current). */
std::string describeCurrentGl()
{
    auto text = [](GLenum name) {
        const GLubyte* value = glGetString(name);
        return value ? std::string(reinterpret_cast<const char*>(value)) : std::string("?");
    };
    return text(GL_VENDOR) + " | " + text(GL_RENDERER) + " | " + text(GL_VERSION);
}

/** A viewer drawing the scene into the context, its camera framing the scene's bound from the front, above. */
osg::ref_ptr<osgViewer::Viewer> makeViewer(osg::GraphicsContext* context, osg::Node* scene, const Options& options,
                                           FinishAndRead* finish)
{
    osg::ref_ptr<osgViewer::Viewer> viewer = new osgViewer::Viewer;
    osg::Camera* camera = viewer->getCamera();
    camera->setGraphicsContext(context);
    camera->setViewport(0, 0, options.width, options.height);
    camera->setProjectionMatrixAsPerspective(30.0, double(options.width) / options.height, 0.1, 1000.0);
    camera->setClearColor(osg::Vec4(0.2f, 0.2f, 0.25f, 1.0f));
    camera->setDrawBuffer(GL_BACK);
    camera->setReadBuffer(GL_BACK);
    camera->setFinalDrawCallback(finish);
    if (!options.smallFeatureCulling)
        camera->setCullingMode(camera->getCullingMode() & ~osg::CullSettings::SMALL_FEATURE_CULLING);
    viewer->setSceneData(scene);
    viewer->setThreadingModel(options.drawThread ? osgViewer::Viewer::DrawThreadPerContext
                                                 : osgViewer::Viewer::SingleThreaded);
    viewer->getViewerStats()->collectStats("update", true);
    camera->getStats()->collectStats("rendering", true);
#if !OSGACTOR_DRAW_BENCH_OSMESA
    // OSMesa has no timer queries (OSG's GPU statistics leave an invalid-operation error there).
    camera->getStats()->collectStats("gpu", true);
#endif
    return viewer;
}

void frameTheScene(osgViewer::Viewer& viewer, osg::Node& scene)
{
    osg::ComputeBoundsVisitor bounds;
    scene.accept(bounds);
    const osg::BoundingSphere sphere(bounds.getBoundingBox());
    // The sphere holds the grid's box: from above the grid's diagonal, the crowd fills the picture at 0.85 of the
    // distance that would hold the whole sphere.
    const double distance = sphere.radius() / std::sin(osg::DegreesToRadians(15.0)) * 0.85;
    osg::Vec3d direction(0.3, -1.0, 0.7);
    direction.normalize();
    viewer.getCamera()->setViewMatrixAsLookAt(sphere.center() + direction * distance, sphere.center(),
                                              osg::Vec3d(0, 0, 1));
}

/** The mean of a statistic over the frames [first, last] that have it, in milliseconds; -1 if none has. */
double averageMs(osg::Stats* stats, unsigned first, unsigned last, const std::string& name)
{
    double sum = 0.0;
    int count = 0;
    for (unsigned frame = first; frame <= last; ++frame)
    {
        double value = 0.0;
        if (stats->getAttribute(frame, name, value)) sum += value, ++count;
    }
    return count ? sum / count * 1000.0 : -1.0;
}

struct Result
{
    double msPerFrame = 0, update = -1, cull = -1, draw = -1, gpu = -1;
    unsigned frames = 0;
};

bool runOne(const std::string& system, unsigned n, const Options& options, osg::GraphicsContext* context,
            Result& result)
{
    const osg::Timer_t buildStart = osg::Timer::instance()->tick();
    osg::ref_ptr<osg::Group> scene = makeCrowd(system, n, options);
    if (!scene)
    {
        std::fprintf(stderr, "%s/%u: cannot build the crowd\n", system.c_str(), n);
        return false;
    }
    const double buildSeconds = osg::Timer::instance()->delta_s(buildStart, osg::Timer::instance()->tick());
    osg::ref_ptr<FinishAndRead> finish = new FinishAndRead;
    osg::ref_ptr<osgViewer::Viewer> viewer = makeViewer(context, scene.get(), options, finish.get());
    viewer->realize();
    double t = 0.0;
    // Warm-up: osgAnimation links its channels on the first frames; GL objects are compiled; the camera frames the
    // crowd as it stands once posed.
    viewer->frame(t);
    frameTheScene(*viewer, *scene);
    for (int i = 0; i < 20; ++i) viewer->frame(t += 1.0 / 60.0);
    const osg::Timer_t start = osg::Timer::instance()->tick();
    unsigned frames = 0;
    double elapsed = 0.0;
    // At least 30 frames, and at least the time asked for.
    while (frames < 30 || elapsed < options.seconds)
    {
        viewer->frame(t += 1.0 / 60.0);
        ++frames;
        elapsed = osg::Timer::instance()->delta_s(start, osg::Timer::instance()->tick());
    }
    result.frames = frames;
    result.msPerFrame = elapsed * 1000.0 / frames;
    const unsigned last = viewer->getFrameStamp()->getFrameNumber();
    // OSG keeps the statistics of the last frames only; the GPU's come a frame or two late.
    const unsigned first = last > 20 ? last - 20 : 0;
    result.update = averageMs(viewer->getViewerStats(), first, last - 3, "Update traversal time taken");
    result.cull = averageMs(viewer->getCamera()->getStats(), first, last - 3, "Cull traversal time taken");
    result.draw = averageMs(viewer->getCamera()->getStats(), first, last - 3, "Draw traversal time taken");
    result.gpu = averageMs(viewer->getCamera()->getStats(), first, last - 3, "GPU draw time taken");
    if (!options.imageDir.empty())
    {
        finish->read = true;
        viewer->frame(t += 1.0 / 60.0);
        if (finish->image.valid())
            osgDB::writeImageFile(*finish->image,
                                  options.imageDir + "/" + system + "_" + std::to_string(n) + ".png");
    }
    std::printf("%-26s %6u %9.2f %8.1f %8.2f %8.2f %8.2f %8.2f %7u %7.1f\n", system.c_str(), n, result.msPerFrame,
                1000.0 / result.msPerFrame, result.update, result.cull, result.draw, result.gpu, result.frames,
                buildSeconds);
    std::fflush(stdout);
    // Never taken apart: each crowd's members share nodes (the rigid systems one box geode under every joint), and
    // OSG removes a parent from a node's list by a linear search and erase, which for 300,000 parents of one node
    // costs minutes. The process ends soon after the runs.
    scene->ref();
    viewer->setDone(true);
    viewer->stopThreading();
    // The context outlives this viewer: detach it so that the next viewer can use it.
    viewer->getCamera()->setGraphicsContext(nullptr);
    viewer->getCamera()->setFinalDrawCallback(nullptr);
    return true;
}

/** One Cesium Man, drawn at the same time of its clip by osgActor's GPU path (vertex shader) and CPU path (the
  * skinning job), from the same camera: both images written, and how far they differ printed. The GPU path is tested
  * against the CPU path on OSMesa by the test suite; this is the same check on real hardware. */
bool compareSkinningPaths(const Options& options, osg::GraphicsContext* context)
{
    osg::ref_ptr<osg::Image> images[2];
    osg::Matrixd view;
    const char* const names[2] = {"skinned_osgActor_gpu", "skinned_osgActor_cpu"};
    for (int path = 0; path < 2; ++path)
    {
        osg::ref_ptr<osg::Group> scene = makeCrowd(names[path], 1, options);
        if (!scene) return false;
        osg::ref_ptr<FinishAndRead> finish = new FinishAndRead;
        osg::ref_ptr<osgViewer::Viewer> viewer = makeViewer(context, scene.get(), options, finish.get());
        viewer->realize();
        double t = 0.0;
        viewer->frame(t);
        if (path == 0)
        {
            frameTheScene(*viewer, *scene);
            view = viewer->getCamera()->getViewMatrix();
        }
        viewer->getCamera()->setViewMatrix(view);
        for (int i = 0; i < 30; ++i) viewer->frame(t += 1.0 / 60.0);
        finish->read = true;
        viewer->frame(t += 1.0 / 60.0);
        images[path] = finish->image;
        viewer->setDone(true);
        viewer->stopThreading();
        viewer->getCamera()->setGraphicsContext(nullptr);
        viewer->getCamera()->setFinalDrawCallback(nullptr);
        if (!images[path].valid()) return false;
        osgDB::writeImageFile(*images[path], options.imageDir + "/compare_" + names[path] + ".png");
    }
    const osg::Image& gpu = *images[0];
    const osg::Image& cpu = *images[1];
    unsigned differing = 0, drawn = 0;
    double sumAbs = 0.0;
    const unsigned char* background = gpu.data(0, 0);
    for (int y = 0; y < gpu.t(); ++y)
        for (int x = 0; x < gpu.s(); ++x)
        {
            int largest = 0;
            bool isBackground = true;
            for (int c = 0; c < 3; ++c)
            {
                const int difference = std::abs(int(gpu.data(x, y)[c]) - int(cpu.data(x, y)[c]));
                largest = std::max(largest, difference);
                sumAbs += difference;
                isBackground = isBackground && gpu.data(x, y)[c] == background[c] && cpu.data(x, y)[c] == background[c];
            }
            if (!isBackground) ++drawn;
            if (largest > 24) ++differing;
        }
    std::printf("skinning paths, GPU against CPU: %u of %u character pixels (%.2f%%) differ by more than 24 levels; "
                "mean difference %.3f levels per channel over the image\n",
                differing, drawn, drawn ? 100.0 * differing / drawn : 0.0, sumAbs / (3.0 * gpu.s() * gpu.t()));
    return true;
}

std::vector<std::string> splitWords(const std::string& text)
{
    std::vector<std::string> words;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ','))
        if (!item.empty()) words.push_back(item);
    return words;
}

bool parseOptions(int argc, char** argv, Options& options)
{
    for (int i = 1; i < argc; ++i)
    {
        const std::string argument = argv[i];
        const std::size_t equals = argument.find('=');
        const std::string key = argument.substr(0, equals);
        const std::string value = equals == std::string::npos ? "" : argument.substr(equals + 1);
        bool good = true;
        if (key == "--actors") good = bench::parseCountList(value, 100000, options.actors);
        else if (key == "--systems") good = !(options.systems = splitWords(value)).empty();
        else if (key == "--seconds") good = (options.seconds = std::atof(value.c_str())) > 0.0;
        else if (key == "--size") good = std::sscanf(value.c_str(), "%dx%d", &options.width, &options.height) == 2 &&
                                         options.width > 0 && options.height > 0;
        else if (key == "--threading") good = (options.drawThread = value == "draw") || value == "single";
        else if (key == "--small-features") good = (options.smallFeatureCulling = value == "cull") || value == "draw";
        else if (key == "--device") good = (options.device = std::atoi(value.c_str())) >= 0;
        else if (key == "--images") good = !(options.imageDir = value).empty();
        else if (key == "--cesium-man") good = !(options.cesiumMan = value).empty();
        else good = false;
        if (!good)
        {
            std::fprintf(stderr, "draw bench: bad argument '%s' (see the source's head for usage)\n",
                         argv[i]);
            return false;
        }
    }
    return true;
}

} // namespace

int main(int argc, char** argv)
{
    Options options;
    if (!parseOptions(argc, argv, options)) return 2;
    osg::setNotifyHandler(new OncePerMessage);
    // Every system hangs the same shared box under each joint; the cull benchmarks' 4 cm box is below a pixel from a
    // camera that frames a crowd, so here it is the size of a limb's section, drawn by every system alike.
    bench::jointBox()->setDrawable(0, new osg::ShapeDrawable(new osg::Box(osg::Vec3(), 0.12f)));
    if (!options.imageDir.empty() && !osgDB::makeDirectory(options.imageDir))
    {
        std::fprintf(stderr, "draw bench: cannot make the folder %s\n", options.imageDir.c_str());
        return 1;
    }
    std::string error;
    osg::ref_ptr<HeadlessContext> context =
        HeadlessContext::create(options.width, options.height, options.device, error);
    if (!context)
    {
        std::fprintf(stderr, "draw bench: %s\nEGL devices:\n%s", error.c_str(),
                     HeadlessContext::listDevices().c_str());
        return 1;
    }
    context->makeCurrent();
    std::printf("OpenGL: %s\n", describeCurrentGl().c_str());
    context->releaseContext();
    if (!options.imageDir.empty() && !compareSkinningPaths(options, context.get()))
        std::fprintf(stderr, "draw bench: the skinning paths could not be compared\n");
    std::printf("%-26s %6s %9s %8s %8s %8s %8s %8s %7s %7s\n", "system", "N", "ms/frame", "fps", "update", "cull",
                "draw", "gpu", "frames", "build_s");
    std::map<std::pair<std::string, int>, double> msPerFrame;
    for (int n : options.actors)
        for (const std::string& system : options.systems)
        {
            Result result;
            if (runOne(system, unsigned(n), options, context.get(), result))
                msPerFrame[{system, n}] = result.msPerFrame;
        }
    std::printf("\n%-26s %6s %14s %14s\n", "system", "N", "/osgAnimation", "/plainOSG");
    for (const auto& entry : msPerFrame)
    {
        const std::string& system = entry.first.first;
        const bool skinned = system.rfind("skinned_", 0) == 0;
        const std::string peerName = skinned ? "skinned_osgAnimation_hw" : "rigid_osgAnimation";
        const auto peer = msPerFrame.find({peerName, entry.first.second});
        const auto plain = msPerFrame.find({"rigid_plainOSG", entry.first.second});
        std::printf("%-26s %6d %14.3f %14.3f\n", system.c_str(), entry.first.second,
                    peer != msPerFrame.end() ? entry.second / peer->second : 0.0,
                    !skinned && plain != msPerFrame.end() ? entry.second / plain->second : 0.0);
    }
    return 0;
}
