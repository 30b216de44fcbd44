#include "ShowcaseScene.h"
#include "LightNumberShadowMap.h"
#include "LoopTrajectory.h"
#include "PathWalker.h"
#include "RetargetedDance.h"
#include "TripodGait.h"

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/LightSource>
#include <osg/Material>
#include <osg/MatrixTransform>
#include <osg/Notify>
#include <osg/ProxyNode>
#include <osg/ShapeDrawable>
#include <osgShadow/ShadowedScene>

#include <cmath>
#include <functional>

namespace osgActorShowcase {

namespace {

// The stage, metres, Z up; the default camera looks from -Y.
const osg::Vec3d kDancerSpot(0.0, 1.3, 0.0);
// Cesium Man dancing the dancer's motion retargeted onto him stands beside it, a little closer to the camera, so the
// two are seen side by side.
const osg::Vec3d kRetargetedDancerSpot = kDancerSpot + osg::Vec3d(-1.0, -0.2, 0.0);
const osg::Vec3d kInsectArea(4.4, 1.3, 0.0);
const double kInsectScale = 0.8;
const int kSunLightNumber = 1; // the viewer's headlight is 0
// Texels of the shadow map each way: over the casters' bound (about 10 m across), a texel of about 5 mm.
const int kShadowMapSize = 2048;

osg::ref_ptr<osg::Material> makeMaterial(const osg::Vec4& colour)
{
    osg::ref_ptr<osg::Material> material = new osg::Material;
    material->setDiffuse(osg::Material::FRONT_AND_BACK, colour);
    material->setAmbient(osg::Material::FRONT_AND_BACK, colour * 0.4f);
    return material;
}

osg::ref_ptr<osg::Geode> makeShape(osg::Shape* shape, const osg::Vec4& colour)
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(new osg::ShapeDrawable(shape));
    geode->getOrCreateStateSet()->setAttributeAndModes(makeMaterial(colour).get());
    return geode;
}

/** A checkered floor of 1 m tiles on z = 0, one geometry with a colour per vertex. */
osg::ref_ptr<osg::Geode> makeFloor(const osg::Vec3d& centre, int tilesX, int tilesY)
{
    osg::ref_ptr<osg::Vec3Array> vertices = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec4Array> colours = new osg::Vec4Array;
    const osg::Vec4 light(0.78f, 0.76f, 0.68f, 1.0f);
    const osg::Vec4 dark(0.55f, 0.58f, 0.5f, 1.0f);
    const osg::Vec3d corner = centre - osg::Vec3d(tilesX * 0.5, tilesY * 0.5, 0.0);
    for (int j = 0; j < tilesY; ++j)
        for (int i = 0; i < tilesX; ++i)
        {
            const osg::Vec3d p = corner + osg::Vec3d(i, j, 0.0);
            for (const osg::Vec3d& v : {p, p + osg::Vec3d(1, 0, 0), p + osg::Vec3d(1, 1, 0), p + osg::Vec3d(0, 1, 0)})
            {
                vertices->push_back(v);
                colours->push_back((i + j) % 2 == 0 ? light : dark);
            }
        }
    osg::ref_ptr<osg::Geometry> geometry = new osg::Geometry;
    geometry->setVertexArray(vertices.get());
    geometry->setColorArray(colours.get(), osg::Array::BIND_PER_VERTEX);
    osg::ref_ptr<osg::Vec3Array> normals = new osg::Vec3Array;
    normals->push_back(osg::Vec3(0.0f, 0.0f, 1.0f));
    geometry->setNormalArray(normals.get(), osg::Array::BIND_OVERALL);
    geometry->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, GLsizei(vertices->size())));

    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->setName("floor");
    geode->addDrawable(geometry.get());
    osg::ref_ptr<osg::Material> material = new osg::Material;
    material->setColorMode(osg::Material::AMBIENT_AND_DIFFUSE); // the vertex colours, lit
    geode->getOrCreateStateSet()->setAttributeAndModes(material.get());
    return geode;
}

/** The sun: a directional light (number 1; the viewer's headlight is 0) from the left and a little in front, high
  * up, so that the actors' shadows fall to the right of them, where the camera sees them. */
osg::ref_ptr<osg::LightSource> makeSun(osg::StateSet& rootState)
{
    osg::ref_ptr<osg::Light> light = new osg::Light(kSunLightNumber);
    light->setPosition(osg::Vec4(-0.8f, -0.45f, 1.0f, 0.0f)); // w = 0: a direction, towards the light
    light->setDiffuse(osg::Vec4(0.75f, 0.72f, 0.65f, 1.0f));
    light->setAmbient(osg::Vec4(0.2f, 0.2f, 0.22f, 1.0f));
    light->setSpecular(osg::Vec4(0.0f, 0.0f, 0.0f, 1.0f));
    osg::ref_ptr<osg::LightSource> sun = new osg::LightSource;
    sun->setName("sun");
    sun->setLight(light.get());
    // Relative to the frame above it (the scene's root: world space), so that it stays put as the camera moves and
    // the shadows fall the same way from every view.
    sun->setReferenceFrame(osg::LightSource::RELATIVE_RF);
    sun->setLocalStateSetModes(osg::StateAttribute::ON);
    sun->setStateSetModes(rootState, osg::StateAttribute::ON);
    return sun;
}

osg::ref_ptr<osg::ProxyNode> makeProxy(const std::string& file, const std::string& name)
{
    osg::ref_ptr<osg::ProxyNode> proxy = new osg::ProxyNode;
    proxy->setName(name);
    proxy->setFileName(0, file);
    return proxy;
}

/** The obstacles the insect wanders among: two rocks inside the loops of its figure of eight, crates outside. */
osg::ref_ptr<osg::Group> makeObstacles()
{
    osg::ref_ptr<osg::Group> obstacles = new osg::Group;
    obstacles->setName("obstacles");
    const osg::Vec4 rock(0.5f, 0.47f, 0.45f, 1.0f);
    const osg::Vec4 crate(0.6f, 0.42f, 0.22f, 1.0f);
    for (double side : {-1.0, 1.0})
    {
        const osg::Vec3d centre = kInsectArea + osg::Vec3d(side * 1.0, 0.0, 0.0);
        obstacles->addChild(makeShape(new osg::Sphere(osg::Vec3(centre), 0.32f), rock));
    }
    obstacles->addChild(makeShape(new osg::Box(osg::Vec3(kInsectArea + osg::Vec3d(0.0, 1.5, 0.3)), 0.6f), crate));
    obstacles->addChild(makeShape(new osg::Box(osg::Vec3(kInsectArea + osg::Vec3d(0.3, -1.4, 0.2)), 0.4f), crate));
    obstacles->addChild(makeShape(new osg::Cylinder(osg::Vec3(kInsectArea + osg::Vec3d(2.4, 0.9, 0.4)), 0.15f, 0.8f),
                                  rock));
    return obstacles;
}

/** A stored loop round a curve; the curves here are the scene's own, so a refusal is a bug worth a loud warning. */
osgActor::TrajectoryPtr makeStoredLoop(const std::string& name, const std::function<osg::Vec3d(double)>& curve,
                                       double speed)
{
    const osgActor::TrajectoryBuildResult built = makeLoopTrajectory(name, curve, speed);
    if (!built) OSG_WARN << "osgactorshowcase: " << built.error << std::endl;
    return built.trajectory;
}

osg::ref_ptr<osg::Group> makeWalker(const ShowcaseSources& sources)
{
    osg::ref_ptr<osg::Group> group = new osg::Group;
    group->setName("walker");
    osg::ref_ptr<PathWalker> walker = new PathWalker;
    const double a = 2.0;
    const double b = 1.2;
    // Anticlockwise round the dancer, at the speed the walker's walk suits.
    walker->setPath(makeStoredLoop(
        "walker round the dancer",
        [&](double s) {
            return kDancerSpot + osg::Vec3d(a * std::cos(2.0 * osg::PI * s), b * std::sin(2.0 * osg::PI * s), 0.0);
        },
        sources.walkerSpeed));
    walker->setCycleDuration(sources.walkerCycleDuration);
    group->setUpdateCallback(walker.get());
    group->addChild(makeProxy(sources.walker, "walker").get());
    return group;
}

osg::ref_ptr<osg::Group> makeWanderingInsect(const std::string& file)
{
    // The insect lives in a frame scaled down (a cockroach a metre long would be large even here); its path is
    // given in that frame.
    osg::ref_ptr<osg::MatrixTransform> group =
        new osg::MatrixTransform(osg::Matrixd::scale(osg::Vec3d(1, 1, 1) * kInsectScale));
    group->setName("wandering insect");
    group->getOrCreateStateSet()->setMode(GL_RESCALE_NORMAL, osg::StateAttribute::ON);
    osg::ref_ptr<TripodGait> gait = new TripodGait;
    // A figure of eight round the two rocks, at 0.3 m/s (in the world).
    gait->setPath(makeStoredLoop(
        "insect among the rocks",
        [](double s) {
            const double t = 2.0 * osg::PI * s;
            const osg::Vec3d world = kInsectArea + osg::Vec3d(1.8 * std::sin(t), 0.9 * std::sin(2.0 * t), 0.0);
            return world / kInsectScale;
        },
        0.3 / kInsectScale));
    gait->setCycleDuration(0.7);
    gait->setStepHeight(0.1);
    group->setUpdateCallback(gait.get());
    group->addChild(makeProxy(file, "insect").get());
    return group;
}

osg::ref_ptr<osg::Node> makeDancer(const ShowcaseSources& sources)
{
    osg::Matrixd placement = osg::Matrixd::scale(osg::Vec3d(1, 1, 1) * sources.dancerScale);
    if (sources.dancerYUp) placement = placement * osg::Matrixd::rotate(osg::PI_2, osg::Vec3d(1, 0, 0));
    placement = placement * osg::Matrixd::translate(kDancerSpot);
    osg::ref_ptr<osg::MatrixTransform> transform = new osg::MatrixTransform(placement);
    transform->setName("dancer");
    transform->getOrCreateStateSet()->setMode(GL_RESCALE_NORMAL, osg::StateAttribute::ON);
    transform->addChild(makeProxy(sources.dancer, "dancer").get());
    return transform;
}

/** The walker's model dancing the dancer's motion, retargeted onto him at load (RetargetedDance), beside the dancer. */
osg::ref_ptr<osg::Group> makeRetargetedDancer(const ShowcaseSources& sources)
{
    osg::ref_ptr<osg::Group> group = new osg::Group;
    group->setName("retargeted dancer");
    osg::ref_ptr<RetargetedDance> dance = new RetargetedDance;
    dance->setSkeletonFile(sources.danceSkeleton);
    dance->setMotionFile(sources.danceMotion);
    group->setUpdateCallback(dance.get());
    osg::ref_ptr<osg::MatrixTransform> place = new osg::MatrixTransform(osg::Matrixd::translate(kRetargetedDancerSpot));
    place->addChild(makeProxy(sources.walker, "retargeted dancer").get());
    group->addChild(place.get());
    return group;
}

} // namespace

osg::ref_ptr<osg::Group> makeShowcaseScene(const ShowcaseSources& sources)
{
    // The sun casts the shadows (not a viewer's headlight). Everything casts and receives, but the floor, which only
    // receives (it would shadow nothing, and the shadow map then holds the actors and obstacles alone).
    osg::ref_ptr<LightNumberShadowMap> shadowMap = new LightNumberShadowMap;
    shadowMap->setLightNumber(kSunLightNumber);
    shadowMap->setTextureSize(osg::Vec2s(kShadowMapSize, kShadowMapSize));
    osg::ref_ptr<osgShadow::ShadowedScene> root = new osgShadow::ShadowedScene(shadowMap.get());
    root->setName("osgActor showcase");
    root->setReceivesShadowTraversalMask(kReceivesShadowMask);
    root->setCastsShadowTraversalMask(kCastsShadowMask);
    root->addChild(makeSun(*root->getOrCreateStateSet()).get());
    osg::ref_ptr<osg::Geode> floor = makeFloor(osg::Vec3d(1.8, 1.3, 0.0), 16, 10);
    floor->setNodeMask(kReceivesShadowMask);
    root->addChild(floor.get());
    root->addChild(makeObstacles().get());
    root->addChild(makeWalker(sources).get());
    root->addChild(makeWanderingInsect(sources.insect).get());
    if (!sources.dancer.empty()) root->addChild(makeDancer(sources).get());
    // Source and target side by side: no dancer, no retargeted copy of its dance.
    if (!sources.dancer.empty() && !sources.danceMotion.empty()) root->addChild(makeRetargetedDancer(sources).get());
    return root;
}

} // namespace osgActorShowcase
