// The Assimp reader's animations (AssimpScene): each aiNodeAnim's position, rotation and scaling keys as channels of
// its node, with Assimp's interpolation (linear positions and scales, spherical linear rotations) and times in
// seconds.
#include "AssimpScene"

#include <glm/ext/quaternion_geometric.hpp>

#include <cmath>
#include <limits>

namespace osgActor {
namespace assimp {

namespace {

/** The ticks per second Assimp's own viewer assumes where a file gives none. */
constexpr double kDefaultTicksPerSecond = 25.0;

const char* behaviourName(aiAnimBehaviour behaviour)
{
    switch (behaviour)
    {
    case aiAnimBehaviour_LINEAR: return "LINEAR";
    case aiAnimBehaviour_REPEAT: return "REPEAT";
    default: return nullptr;
    }
}

glm::dvec4 valueOf(const aiVectorKey& key) { return glm::dvec4(key.mValue.x, key.mValue.y, key.mValue.z, 0.0); }
glm::dvec4 valueOf(const aiQuatKey& key) { return glm::dvec4(key.mValue.x, key.mValue.y, key.mValue.z, key.mValue.w); }

class AnimationReader
{
public:
    AnimationReader(SceneReading& reading, unsigned index)
        : _reading(reading), _source(*reading.scene.mAnimations[index]),
          _place(place("animations", index, reading.scene.mAnimations[index]->mName))
    {
    }

    RiggedAnimation read()
    {
        RiggedAnimation animation;
        animation.name = _source.mName.C_Str(); // "animation<i>" when empty (makeAnimationNamesUnique)
        double ticksPerSecond = _source.mTicksPerSecond;
        if (ticksPerSecond == 0.0)
        {
            ticksPerSecond = kDefaultTicksPerSecond;
            _reading.warn(_place + ": the file gives no ticks per second; 25 are assumed, as Assimp's viewer does");
        }
        if (!(ticksPerSecond > 0.0) || !std::isfinite(ticksPerSecond))
            throw Refusal(_place, "its ticks per second (" + std::to_string(_source.mTicksPerSecond) +
                                      ") is not a positive number");
        if (_source.mNumMeshChannels > 0 || _source.mNumMorphMeshChannels > 0)
            _reading.warn(_place + ": its mesh and morph channels are left out");
        if (_source.mNumChannels > 0 && !_source.mChannels) throw Refusal(_place, "has no list of its channels");
        for (unsigned c = 0; c < _source.mNumChannels; ++c)
        {
            const aiNodeAnim* channel = _source.mChannels[c];
            if (!channel) throw Refusal(_place, "channels[" + std::to_string(c) + "] is missing");
            const std::string where = _place + "." + place("channels", c, channel->mNodeName);
            const int node = _reading.findNode(channel->mNodeName);
            if (node < 0)
            {
                _reading.warn(where + ": animates no node of the scene and is left out");
                continue;
            }
            for (aiAnimBehaviour behaviour : {channel->mPreState, channel->mPostState})
                if (const char* name = behaviourName(behaviour))
                    _reading.warn(where + ": " + name + " outside its keys is not supported; the nearest key is held");
            addChannel(animation, node, AnimationPath::Translation, channel->mPositionKeys,
                       channel->mNumPositionKeys, ticksPerSecond, where + ".positionKeys");
            addChannel(animation, node, AnimationPath::Rotation, channel->mRotationKeys, channel->mNumRotationKeys,
                       ticksPerSecond, where + ".rotationKeys");
            addChannel(animation, node, AnimationPath::Scale, channel->mScalingKeys, channel->mNumScalingKeys,
                       ticksPerSecond, where + ".scalingKeys");
        }
        double moved = 0.0;
        if (!startAnimationAtZero(animation, moved))
            throw Refusal(_place, "its keys start at " + std::to_string(-moved) +
                                      " s, too early to move them to 0 and still tell them apart");
        if (moved > 0.0)
            _reading.warn(_place + ": its keys start at " + std::to_string(-moved) + " s; they are moved to start at 0");
        return animation;
    }

private:
    template <class Key>
    void addChannel(RiggedAnimation& animation, int node, AnimationPath path, const Key* keys, unsigned count,
                    double ticksPerSecond, const std::string& where) const
    {
        if (count == 0) return;
        if (!keys) throw Refusal(where, "has no list of its keys");
        AnimationChannel channel;
        channel.node = node;
        channel.path = path;
        channel.interpolation = KeyInterpolation::Linear; // spherical for rotations (sampleRotationChannel)
        for (unsigned k = 0; k < count; ++k)
        {
            const double time = keys[k].mTime / ticksPerSecond;
            glm::dvec4 value = valueOf(keys[k]);
            if (!std::isfinite(time) || !std::isfinite(value.x) || !std::isfinite(value.y) ||
                !std::isfinite(value.z) || !std::isfinite(value.w))
                throw Refusal(where, "key " + std::to_string(k) + " holds a number that is not finite");
            if (k > 0 && !(time > channel.times.back()))
                throw Refusal(where, "key times are not strictly increasing at key " + std::to_string(k));
            if (path == AnimationPath::Rotation)
            {
                const double length = glm::length(value);
                if (!(length > 1e-6)) throw Refusal(where, "key " + std::to_string(k) + " is a zero quaternion");
                value /= length;
            }
            channel.times.push_back(time);
            channel.values.push_back(value);
        }
        animation.channels.push_back(std::move(channel));
    }

    SceneReading& _reading;
    const aiAnimation& _source;
    const std::string _place;
};

} // namespace

void readAnimations(SceneReading& reading)
{
    const aiScene& scene = reading.scene;
    if (scene.mNumAnimations > 0 && !scene.mAnimations) throw Refusal("scene", "has no list of its animations");
    for (unsigned a = 0; a < scene.mNumAnimations; ++a)
    {
        if (!scene.mAnimations[a]) throw Refusal("animations[" + std::to_string(a) + "]", "is missing");
        reading.model.animations.push_back(AnimationReader(reading, a).read());
    }
}

} // namespace assimp
} // namespace osgActor
