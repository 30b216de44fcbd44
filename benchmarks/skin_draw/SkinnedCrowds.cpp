#include "SkinnedCrowds"

#include <osgActor/GlmOsg>
#include <osgActor/InstancedActorGroup>
#include <osgActor/RiggedGeometry>
#include <osgActor/RiggedModelActor>
#include <osgActor/import/RiggedModelFile>

#include <osg/Geode>
#include <osg/MatrixTransform>
#include <osgAnimation/BasicAnimationManager>
#include <osgAnimation/Bone>
#include <osgAnimation/RigGeometry>
#include <osgAnimation/RigTransformHardware>
#include <osgAnimation/RigTransformSoftware>
#include <osgAnimation/Skeleton>
#include <osgAnimation/StackedQuaternionElement>
#include <osgAnimation/StackedScaleElement>
#include <osgAnimation/StackedTranslateElement>
#include <osgAnimation/UpdateBone>

#include <iostream>
#include <map>

namespace bench {

namespace {

/** group: null for a plain group of the file's scene nodes, else the group to put the actors in. */
osg::ref_ptr<osg::Group> makeOsgActorCrowd(unsigned n, bool cpu, const std::string& file,
                                           osgActor::InstancedActorGroup* group = nullptr, unsigned groupThreads = 1)
{
    osgActor::RiggedModelActorOptions options;
    options.skinning = cpu ? osgActor::SkinnedMesh::CPU_SKINNING : osgActor::SkinnedMesh::GPU_SKINNING;
    std::string error;
    const osgActor::RiggedModelActor read = osgActor::readRiggedModelActor(file, options, error);
    if (!read.actor)
    {
        std::cerr << error << "\n";
        return nullptr;
    }
    osg::ref_ptr<osg::Group> crowd = new osg::Group;
    if (!group)
    {
        for (unsigned a = 0; a < n; ++a) crowd->addChild(osg::clone(read.sceneNode.get(), osg::CopyOp::SHALLOW_COPY));
        return crowd;
    }
    // The group's children must be the actors: the file's root scale (a transform above the actor, if any) goes
    // above the group.
    group->setNumThreads(groupThreads);
    for (unsigned a = 0; a < n; ++a) group->addChild(osg::clone(read.actor.get(), osg::CopyOp::SHALLOW_COPY));
    if (read.sceneNode == read.actor)
    {
        crowd->addChild(group);
        return crowd;
    }
    osg::ref_ptr<osg::Group> above = static_cast<osg::Group*>(read.sceneNode->clone(osg::CopyOp::SHALLOW_COPY));
    above->removeChildren(0, above->getNumChildren());
    above->addChild(group);
    crowd->addChild(above.get());
    return crowd;
}

osg::ref_ptr<osg::Group> makeOsgActorGroupCrowd(unsigned n, osgActor::InstancedActorGroup::DrawMode mode,
                                                const std::string& file, unsigned threads)
{
    osg::ref_ptr<osgActor::InstancedActorGroup> group = new osgActor::InstancedActorGroup;
    group->setDrawMode(mode);
    return makeOsgActorCrowd(n, false, file, group.get(), threads);
}

bool isUnit(const glm::dvec3& scale) { return glm::length(scale - glm::dvec3(1.0)) < 1e-5; }

/** One osgAnimation Cesium Man in the file's axes (Y up) below a turn to Z up, its manager not playing yet. */
osg::ref_ptr<osg::Group> makeOneOsgAnimationMan(const osgActor::RiggedModel& model, bool hardware)
{
    // The skinned primitive, its skin, and the nodes that become bones: the skin's joints and their ancestors.
    int meshIndex = -1, skinIndex = -1;
    for (const osgActor::RiggedNode& node : model.nodes)
        if (node.skin >= 0) meshIndex = node.mesh, skinIndex = node.skin;
    const osgActor::RiggedSkin& skin = model.skins[skinIndex];
    const osgActor::RiggedPrimitive& primitive = model.meshes[meshIndex].primitives[0];
    std::vector<bool> isBone(model.nodes.size(), false);
    for (int joint : skin.joints)
        for (int node = joint; node >= 0; node = model.nodes[node].parent) isBone[node] = true;

    osg::ref_ptr<osgAnimation::Skeleton> skeleton = new osgAnimation::Skeleton;
    skeleton->setDefaultUpdateCallback();
    std::map<int, osgAnimation::Bone*> bones;
    // Parents before children: nodes may come in any order, so add each once its parent is there.
    for (bool added = true; added;)
    {
        added = false;
        for (int i = 0; i < int(model.nodes.size()); ++i)
        {
            const osgActor::RiggedNode& node = model.nodes[i];
            if (!isBone[i] || bones.count(i) || (node.parent >= 0 && !bones.count(node.parent))) continue;
            osgAnimation::Bone* bone = new osgAnimation::Bone(node.name);
            bone->setDefaultUpdateCallback();
            osgAnimation::UpdateBone* update = dynamic_cast<osgAnimation::UpdateBone*>(bone->getUpdateCallback());
            update->getStackedTransforms().push_back(
                new osgAnimation::StackedTranslateElement("translate", osg::Vec3(osgActor::toOsg(node.translation))));
            update->getStackedTransforms().push_back(
                new osgAnimation::StackedQuaternionElement("quaternion", osgActor::toOsg(node.rotation)));
            if (!isUnit(node.scale))
                update->getStackedTransforms().push_back(
                    new osgAnimation::StackedScaleElement("scale", osg::Vec3(osgActor::toOsg(node.scale))));
            (node.parent >= 0 ? static_cast<osg::Group*>(bones[node.parent]) : skeleton.get())->addChild(bone);
            bones[i] = bone;
            added = true;
        }
    }
    for (std::size_t j = 0; j < skin.joints.size(); ++j)
        bones[skin.joints[j]]->setInvBindMatrixInSkeletonSpace(osgActor::toOsg(skin.inverseBindMatrices[j]));

    // The mesh as osgActor draws it rigidly, with the same material, and its influences by bone name.
    osg::ref_ptr<osg::Geometry> source = osgActor::createPrimitiveGeometry(model, primitive);
    source->setStateSet(osgActor::createMaterialStateSet(model, primitive.material).get());
    osg::ref_ptr<osgAnimation::VertexInfluenceMap> influences = new osgAnimation::VertexInfluenceMap;
    const unsigned perVertex = primitive.influencesPerVertex;
    for (unsigned v = 0; v < primitive.getNumVertices(); ++v)
    {
        double sum = 0.0;
        for (unsigned k = 0; k < perVertex; ++k) sum += primitive.weights[v * perVertex + k];
        for (unsigned k = 0; k < perVertex; ++k)
        {
            const float weight = float(primitive.weights[v * perVertex + k] / sum);
            if (weight == 0.0f) continue;
            const std::string& bone = model.nodes[skin.joints[primitive.joints[v * perVertex + k]]].name;
            osgAnimation::VertexInfluence& influence = (*influences)[bone];
            influence.setName(bone);
            influence.push_back(osgAnimation::VertexIndexWeight(v, weight));
        }
    }
    osg::ref_ptr<osgAnimation::RigGeometry> rig = new osgAnimation::RigGeometry;
    rig->setSourceGeometry(source.get());
    rig->setInfluenceMap(influences.get());
    rig->setStateSet(source->getStateSet());
    if (hardware)
    {
        osg::ref_ptr<osgAnimation::RigTransformHardware> transform = new osgAnimation::RigTransformHardware;
        transform->setShader(new osg::Shader(osg::Shader::VERTEX, vertexShaderForRigHardware()));
        rig->setRigTransformImplementation(transform.get());
    }
    else
    {
        rig->setRigTransformImplementation(new osgAnimation::RigTransformSoftware);
    }
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(rig.get());
    skeleton->addChild(geode.get());

    // The file's first animation, on the bones' stacked elements (scale only where a bone has one).
    osg::ref_ptr<osgAnimation::Animation> animation = new osgAnimation::Animation;
    animation->setName(model.animations[0].name);
    for (const osgActor::AnimationChannel& channel : model.animations[0].channels)
    {
        if (!bones.count(channel.node)) continue;
        const std::string& target = model.nodes[channel.node].name;
        if (channel.path == osgActor::AnimationPath::Rotation)
        {
            osg::ref_ptr<osgAnimation::QuatSphericalLinearChannel> rotation = new osgAnimation::QuatSphericalLinearChannel;
            rotation->setName("quaternion");
            rotation->setTargetName(target);
            osgAnimation::QuatKeyframeContainer* keys = rotation->getOrCreateSampler()->getOrCreateKeyframeContainer();
            for (std::size_t k = 0; k < channel.times.size(); ++k)
            {
                const glm::dvec4& q = channel.values[k];
                keys->push_back(osgAnimation::QuatKeyframe(channel.times[k], osg::Quat(q.x, q.y, q.z, q.w)));
            }
            animation->addChannel(rotation.get());
        }
        else if (channel.path == osgActor::AnimationPath::Translation ||
                 (channel.path == osgActor::AnimationPath::Scale && !isUnit(model.nodes[channel.node].scale)))
        {
            osg::ref_ptr<osgAnimation::Vec3LinearChannel> vector = new osgAnimation::Vec3LinearChannel;
            vector->setName(channel.path == osgActor::AnimationPath::Translation ? "translate" : "scale");
            vector->setTargetName(target);
            osgAnimation::Vec3KeyframeContainer* keys = vector->getOrCreateSampler()->getOrCreateKeyframeContainer();
            for (std::size_t k = 0; k < channel.times.size(); ++k)
            {
                const glm::dvec4& t = channel.values[k];
                keys->push_back(osgAnimation::Vec3Keyframe(channel.times[k], osg::Vec3(t.x, t.y, t.z)));
            }
            animation->addChannel(vector.get());
        }
    }
    animation->setPlayMode(osgAnimation::Animation::LOOP);
    animation->computeDuration();

    // glTF is Y up; the osgActor actors stand Z up (RiggedActorOptions::zUp).
    osg::ref_ptr<osg::MatrixTransform> zUp = new osg::MatrixTransform(osg::Matrix::rotate(M_PI / 2, osg::X_AXIS));
    zUp->addChild(skeleton.get());
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(zUp.get());
    osg::ref_ptr<osgAnimation::BasicAnimationManager> manager = new osgAnimation::BasicAnimationManager;
    manager->registerAnimation(animation.get());
    root->setUpdateCallback(manager.get());
    return root;
}

osg::ref_ptr<osg::Group> makeOsgAnimationCrowd(unsigned n, bool hardware, const std::string& file)
{
    const osgActor::RiggedModelRead read = osgActor::readRiggedModelFile(file);
    if (!read)
    {
        std::cerr << read.error << "\n";
        return nullptr;
    }
    osg::ref_ptr<osg::Group> prototype = makeOneOsgAnimationMan(*read.model, hardware);
    osg::ref_ptr<osg::Group> crowd = new osg::Group;
    for (unsigned a = 0; a < n; ++a)
    {
        // Each RigGeometry skins into its own arrays, and the hardware path puts its palette and program in the
        // rig's state set: both per instance.
        osg::ref_ptr<osg::Group> instance = static_cast<osg::Group*>(prototype->clone(
            osg::CopyOp::DEEP_COPY_NODES | osg::CopyOp::DEEP_COPY_CALLBACKS | osg::CopyOp::DEEP_COPY_OBJECTS |
            osg::CopyOp::DEEP_COPY_DRAWABLES | osg::CopyOp::DEEP_COPY_STATESETS));
        osgAnimation::BasicAnimationManager* manager =
            dynamic_cast<osgAnimation::BasicAnimationManager*>(instance->getUpdateCallback());
        manager->playAnimation(manager->getAnimationList().front().get());
        crowd->addChild(instance.get());
    }
    return crowd;
}

} // namespace

const char* nameOf(SkinnedSystem system)
{
    switch (system)
    {
    case SkinnedSystem::OsgActorGpu: return "osgActor_gpu";
    case SkinnedSystem::OsgActorCpu: return "osgActor_cpu";
    case SkinnedSystem::OsgActorGpuGroup: return "osgActor_gpu_group";
    case SkinnedSystem::OsgActorGpuInstanced: return "osgActor_gpu_instanced";
    case SkinnedSystem::OsgAnimationSoftware: return "osgAnimation_software";
    case SkinnedSystem::OsgAnimationHardware: return "osgAnimation_hardware";
    }
    return "";
}

osg::ref_ptr<osg::Group> makeSkinnedCrowd(SkinnedSystem system, unsigned n, const std::string& file,
                                          unsigned groupThreads)
{
    switch (system)
    {
    case SkinnedSystem::OsgActorGpu: return makeOsgActorCrowd(n, false, file);
    case SkinnedSystem::OsgActorCpu: return makeOsgActorCrowd(n, true, file);
    case SkinnedSystem::OsgActorGpuGroup:
        return makeOsgActorGroupCrowd(n, osgActor::InstancedActorGroup::ORDINARY, file, groupThreads);
    case SkinnedSystem::OsgActorGpuInstanced:
        return makeOsgActorGroupCrowd(n, osgActor::InstancedActorGroup::INSTANCED, file, groupThreads);
    case SkinnedSystem::OsgAnimationSoftware: return makeOsgAnimationCrowd(n, false, file);
    case SkinnedSystem::OsgAnimationHardware: return makeOsgAnimationCrowd(n, true, file);
    }
    return nullptr;
}

const char* vertexShaderForRigHardware()
{
    return R"glsl(#version 130
// osgAnimation's hardware skinning interface: up to 8 (palette index, weight) pairs in four attributes. OSG 3.6.5
// sets nbBonesPerVertex as an unsigned int (glUniform1ui), so it is a uint here (GLSL 1.30).
uniform mat4 matrixPalette[MAX_MATRIX];
uniform uint nbBonesPerVertex;
attribute vec4 boneWeight0;
attribute vec4 boneWeight1;
attribute vec4 boneWeight2;
attribute vec4 boneWeight3;

void accumulate(vec4 pairs, int first, int count, inout mat4 blend)
{
    if (first < count) blend += pairs.y * matrixPalette[int(pairs.x)];
    if (first + 1 < count) blend += pairs.w * matrixPalette[int(pairs.z)];
}

void main()
{
    int count = int(nbBonesPerVertex);
    mat4 blend = mat4(0.0);
    accumulate(boneWeight0, 0, count, blend);
    if (count > 2) accumulate(boneWeight1, 2, count, blend);
    if (count > 4) accumulate(boneWeight2, 4, count, blend);
    if (count > 6) accumulate(boneWeight3, 6, count, blend);
    vec4 position = blend * gl_Vertex;
    vec3 normal = normalize(gl_NormalMatrix * (mat3(blend) * gl_Normal));
    gl_Position = gl_ModelViewProjectionMatrix * position;
    // Light 0, directional, diffuse and ambient: what fixed function gives osgActor's materials.
    float diffuse = max(dot(normal, normalize(gl_LightSource[0].position.xyz)), 0.0);
    vec4 colour = gl_FrontLightModelProduct.sceneColor + gl_FrontLightProduct[0].ambient +
                  diffuse * gl_FrontLightProduct[0].diffuse;
    gl_FrontColor = vec4(clamp(colour.rgb, 0.0, 1.0), gl_FrontMaterial.diffuse.a);
    gl_TexCoord[0] = gl_MultiTexCoord0;
}
)glsl";
}

} // namespace bench
