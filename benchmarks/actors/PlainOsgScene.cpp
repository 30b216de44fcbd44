#include "BenchHumanoid"
#include "PeerScenes"

#include <osg/MatrixTransform>
#include <osg/ShapeDrawable>

#include <cmath>
#include <vector>

namespace bench {

osg::ref_ptr<osg::Geode> jointBox()
{
    static osg::ref_ptr<osg::Geode> box = [] {
        osg::ref_ptr<osg::Geode> geode = new osg::Geode;
        geode->addDrawable(new osg::ShapeDrawable(new osg::Box(osg::Vec3(), 0.04f)));
        return geode;
    }();
    return box;
}

bool outOfView(unsigned i, double share)
{
    // Instance i is out when the count out among the first i + 1 grows: evenly spread, exact for any share.
    return static_cast<unsigned>((i + 1) * share) > static_cast<unsigned>(i * share);
}

osg::Vec3d outOfViewPosition() { return osg::Vec3d(0.0, -40.0, 0.0); } // FrameLoop's camera is at y = -8, facing +y

void placeInstances(osg::Group& scene, double share)
{
    for (unsigned i = 0; i < scene.getNumChildren(); ++i)
    {
        osg::ref_ptr<osg::MatrixTransform> place = new osg::MatrixTransform;
        if (outOfView(i, share)) place->setMatrix(osg::Matrixd::translate(outOfViewPosition()));
        place->addChild(scene.getChild(i));
        scene.setChild(i, place.get());
    }
}

osg::Quat eulerXYZ(const double* angles)
{
    // Rx * Ry * Rz in column notation; OSG's row-vector product of the same rotations reads right to left.
    return osg::Quat(angles[2], osg::Z_AXIS) * osg::Quat(angles[1], osg::Y_AXIS) * osg::Quat(angles[0], osg::X_AXIS);
}

namespace {

/** The clip of one joint as quaternion keys, as a plain OSG application would store it. */
struct JointTrack
{
    std::vector<osg::Quat> rotations;
    std::vector<osg::Vec3d> positions; // the offset, plus the root's travel on the root
};

/** One update callback per joint: samples its own track and sets the joint's matrix. */
class JointSampler : public osg::NodeCallback
{
public:
    explicit JointSampler(std::shared_ptr<const JointTrack> track) : _track(std::move(track)) {}
    void operator()(osg::Node* node, osg::NodeVisitor* nv) override
    {
        const BenchClip& clip = humanoidClip();
        const double frame =
            std::fmod(nv->getFrameStamp()->getSimulationTime(), clip.duration()) * clip.framesPerSecond;
        const unsigned f0 = static_cast<unsigned>(frame);
        const unsigned f1 = std::min(f0 + 1, clip.numFrames - 1);
        const double alpha = frame - f0;
        osg::Quat rotation;
        rotation.slerp(alpha, _track->rotations[f0], _track->rotations[f1]);
        const osg::Vec3d position = _track->positions[f0] * (1.0 - alpha) + _track->positions[f1] * alpha;
        static_cast<osg::MatrixTransform*>(node)->setMatrix(osg::Matrixd::rotate(rotation) *
                                                            osg::Matrixd::translate(position));
        traverse(node, nv);
    }

private:
    std::shared_ptr<const JointTrack> _track;
};

std::vector<std::shared_ptr<const JointTrack>> makeTracks()
{
    const std::vector<BenchJoint>& joints = humanoidJoints();
    const BenchClip& clip = humanoidClip();
    std::vector<std::shared_ptr<const JointTrack>> tracks;
    for (unsigned j = 0; j < joints.size(); ++j)
    {
        auto track = std::make_shared<JointTrack>();
        const osg::Vec3d offset(joints[j].offset[0], joints[j].offset[1], joints[j].offset[2]);
        for (unsigned f = 0; f < clip.numFrames; ++f)
        {
            track->rotations.push_back(eulerXYZ(clip.anglesAt(f, j)));
            const double* p = &clip.rootPosition[f * 3];
            track->positions.push_back(j == 0 ? offset + osg::Vec3d(p[0], p[1], p[2]) : offset);
        }
        tracks.push_back(track);
    }
    return tracks;
}

} // namespace

osg::ref_ptr<osg::Group> makePlainOsgScene(unsigned numActors)
{
    const std::vector<BenchJoint>& joints = humanoidJoints();
    const std::vector<std::shared_ptr<const JointTrack>> tracks = makeTracks();
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    for (unsigned a = 0; a < numActors; ++a)
    {
        std::vector<osg::MatrixTransform*> nodes;
        for (unsigned j = 0; j < joints.size(); ++j)
        {
            osg::MatrixTransform* node = new osg::MatrixTransform;
            node->setDataVariance(osg::Object::DYNAMIC);
            node->setUpdateCallback(new JointSampler(tracks[j]));
            node->addChild(jointBox().get());
            if (joints[j].parent < 0) scene->addChild(node);
            else nodes[static_cast<unsigned>(joints[j].parent)]->addChild(node);
            nodes.push_back(node);
        }
    }
    return scene;
}

} // namespace bench
