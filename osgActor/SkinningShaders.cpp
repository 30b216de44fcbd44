#include <osgActor/SkinningShaders>

#include <osgActor/shaders/ShaderSources.h>

#include <osg/State>
#include <osg/Uniform>

#include <map>
#include <mutex>
#include <sstream>
#include <tuple>

namespace osgActor {

namespace {

/** What every compatibility-profile shader starts with after its #version line: the built-in names. */
const char* const kCompatibilityNames = R"glsl(
#define OSGACTOR_ATTRIBUTE attribute
#define OSGACTOR_VARYING_OUT varying
#define OSGACTOR_VARYING_IN varying
#define OSGACTOR_VERTEX gl_Vertex
#define OSGACTOR_NORMAL gl_Normal
#define OSGACTOR_TEXCOORD0 gl_MultiTexCoord0
#define OSGACTOR_MODEL_VIEW gl_ModelViewMatrix
#define OSGACTOR_MODEL_VIEW_PROJECTION gl_ModelViewProjectionMatrix
#define OSGACTOR_PROJECTION gl_ProjectionMatrix
#define OSGACTOR_NORMAL_MATRIX gl_NormalMatrix
#define OSGACTOR_TEXTURE2D texture2D
#define OSGACTOR_FRAG_COLOUR gl_FragColor
)glsl";

/** The core profile's: OSG's aliases, which osg::State binds and sets when it aliases vertex attributes. */
const char* const kCoreVertexNames = R"glsl(
#define OSGACTOR_ATTRIBUTE in
#define OSGACTOR_VARYING_OUT out
in vec4 osg_Vertex;
in vec3 osg_Normal;
in vec4 osg_MultiTexCoord0;
uniform mat4 osg_ModelViewMatrix;
uniform mat4 osg_ModelViewProjectionMatrix;
uniform mat4 osg_ProjectionMatrix;
uniform mat3 osg_NormalMatrix;
#define OSGACTOR_VERTEX osg_Vertex
#define OSGACTOR_NORMAL osg_Normal
#define OSGACTOR_TEXCOORD0 osg_MultiTexCoord0
#define OSGACTOR_MODEL_VIEW osg_ModelViewMatrix
#define OSGACTOR_MODEL_VIEW_PROJECTION osg_ModelViewProjectionMatrix
#define OSGACTOR_PROJECTION osg_ProjectionMatrix
#define OSGACTOR_NORMAL_MATRIX osg_NormalMatrix
)glsl";

const char* const kCoreFragmentNames = R"glsl(
#define OSGACTOR_VARYING_IN in
#define OSGACTOR_TEXTURE2D texture
layout(location = 0) out vec4 osgActor_fragColour;
#define OSGACTOR_FRAG_COLOUR osgActor_fragColour
)glsl";

/** The #version line: 3.30 for the core profile; in the compatibility profile 1.20, or 1.50 for the texture buffer's
  * samplerBuffer and texelFetch (GL 3.2 compatibility contexts, which Mesa and the desktop drivers give). */
const char* versionLine(const SkinningProgramKey& key)
{
    if (key.profile == SkinningProfile::Core) return "#version 330\n";
    const bool buffer = key.skinning && (key.palette == SkinPaletteStorage::TextureBuffer ||
                                         key.instancing == SkinInstancing::PerInstance);
    return buffer ? "#version 150 compatibility\n" : "#version 120\n";
}

std::string variantDefines(const SkinningProgramKey& key)
{
    std::ostringstream out;
    out << "#define OSGACTOR_SKINNING " << (key.skinning ? 1 : 0) << "\n";
    out << "#define OSGACTOR_INFLUENCES " << (key.influences == 8 ? 8 : 4) << "\n";
    out << "#define OSGACTOR_DUAL_QUATERNION " << (key.method == SkinningMethod::DualQuaternion ? 1 : 0) << "\n";
    out << "#define OSGACTOR_INVERSE_TRANSPOSE "
        << (key.method == SkinningMethod::LinearBlend && key.inverseTranspose ? 1 : 0) << "\n";
    out << "#define OSGACTOR_PALETTE_BUFFER " << (key.palette == SkinPaletteStorage::TextureBuffer ? 1 : 0) << "\n";
    out << "#define OSGACTOR_PALETTE_VECTORS " << kMaxUniformPaletteVectors << "\n";
    out << "#define OSGACTOR_PALETTE_STRIDE " << paletteStride(key) << "\n";
    out << "#define OSGACTOR_LIGHTS_ON bool[8](";
    for (unsigned i = 0; i < 8; ++i) out << (i ? ", " : "") << ((key.lights >> i) & 1u ? "true" : "false");
    out << ")\n";
    out << "#define OSGACTOR_FIXED_FUNCTION_OUTPUTS " << (key.fragmentProgram ? 1 : 0) << "\n";
    out << "#define OSGACTOR_EYE_LINEAR_UNITS " << static_cast<unsigned>(key.eyeLinearTexGenUnits) << "\n";
    out << "#define OSGACTOR_INSTANCED_ARITHMETIC " << (key.instancing != SkinInstancing::None ? 1 : 0) << "\n";
    out << "#define OSGACTOR_INSTANCED " << (key.instancing == SkinInstancing::PerInstance ? 1 : 0) << "\n";
    return out.str();
}

/** The key with the fields a program without skinning ignores set to their defaults, so that equal programs have
  * equal keys. */
SkinningProgramKey canonical(SkinningProgramKey key)
{
    if (!key.skinning)
    {
        const SkinningProgramKey given = key;
        key = SkinningProgramKey();
        key.profile = given.profile;
        key.skinning = false;
        key.lights = given.lights;
        key.fragmentProgram = given.fragmentProgram;
        key.eyeLinearTexGenUnits = given.eyeLinearTexGenUnits;
    }
    if (key.profile == SkinningProfile::Core)
    {
        key.lights = SkinningProgramKey().lights;
        key.fragmentProgram = nullptr;
    }
    // An instance's palette is in the instances' buffer, whatever the mesh's storage.
    if (key.instancing == SkinInstancing::PerInstance) key.palette = SkinPaletteStorage::TextureBuffer;
    if (!key.fragmentProgram) key.eyeLinearTexGenUnits = 0;
    key.eyeLinearTexGenUnits &= 0xfe; // unit 0's coordinates are the mesh's own
    if (key.influences != 8) key.influences = 4;
    if (key.method == SkinningMethod::DualQuaternion) key.inverseTranspose = false;
    if (key.palette == SkinPaletteStorage::Automatic) key.palette = SkinPaletteStorage::UniformArray;
    return key;
}

} // namespace

SkinningProfile skinningProfileOf(const osg::State* state)
{
    return state && state->getUseVertexAttributeAliasing() && state->getUseModelViewAndProjectionUniforms()
               ? SkinningProfile::Core
               : SkinningProfile::Compatibility;
}

SkinAttributeSlots skinAttributeSlots(SkinningProfile profile)
{
    return profile == SkinningProfile::Core ? SkinAttributeSlots{8, 9, 10} : SkinAttributeSlots{6, 7, 1};
}

bool SkinningProgramKey::operator<(const SkinningProgramKey& other) const
{
    auto tie = [](const SkinningProgramKey& k) {
        return std::make_tuple(k.profile, k.skinning, k.method, k.inverseTranspose, k.influences, k.palette, k.lights,
                               k.fragmentProgram, k.eyeLinearTexGenUnits, k.instancing);
    };
    return tie(*this) < tie(other);
}

bool isFragmentOnlyProgram(const osg::Program& program)
{
    if (program.getNumShaders() == 0) return false;
    for (unsigned i = 0; i < program.getNumShaders(); ++i)
        if (program.getShader(i)->getType() != osg::Shader::FRAGMENT) return false;
    return true;
}

unsigned paletteStride(const SkinningProgramKey& key)
{
    if (key.method == SkinningMethod::DualQuaternion) return 2;
    return key.inverseTranspose ? 6 : 3;
}

std::string skinningShaderSource(const SkinningProgramKey& given, osg::Shader::Type type)
{
    const SkinningProgramKey key = canonical(given);
    const bool core = key.profile == SkinningProfile::Core;
    std::string source = versionLine(key);
    if (type == osg::Shader::VERTEX)
    {
        source += core ? kCoreVertexNames : kCompatibilityNames;
        source += variantDefines(key);
        source += core ? shaders::kLightingCore : shaders::kLightingCompatibility;
        if (key.instancing != SkinInstancing::None) source += shaders::kInstanceData;
        source += shaders::kSkinnedMeshVertex;
    }
    else
    {
        source += core ? kCoreFragmentNames : kCompatibilityNames;
        source += shaders::kSkinnedMeshFragment;
    }
    return source;
}

osg::ref_ptr<osg::Program> createSkinningProgram(const SkinningProgramKey& given)
{
    const SkinningProgramKey key = canonical(given);
    osg::ref_ptr<osg::Program> program = new osg::Program;
    std::ostringstream name;
    name << "osgActor skinned mesh (" << (key.profile == SkinningProfile::Core ? "core" : "compatibility");
    if (key.skinning)
        name << ", " << (key.method == SkinningMethod::DualQuaternion ? "dual quaternions" : "linear blend")
             << (key.inverseTranspose ? ", inverse-transposed normals" : "") << ", " << key.influences
             << " influences, "
             << (key.instancing == SkinInstancing::PerInstance      ? "instanced"
                 : key.palette == SkinPaletteStorage::TextureBuffer ? "texture buffer"
                                                                    : "uniforms")
             << (key.instancing == SkinInstancing::OneAtATime ? ", the instanced arithmetic one at a time" : "");
    else
        name << ", no skinning";
    if (key.fragmentProgram) name << ", with the fragment shaders of '" << key.fragmentProgram->getName() << "'";
    name << ")";
    program->setName(name.str());
    program->addShader(new osg::Shader(osg::Shader::VERTEX, skinningShaderSource(key, osg::Shader::VERTEX)));
    if (key.fragmentProgram)
    {
        // The same shader objects: OSG compiles a shader once per context for every program holding it.
        for (unsigned i = 0; i < key.fragmentProgram->getNumShaders(); ++i)
            program->addShader(const_cast<osg::Shader*>(key.fragmentProgram->getShader(i)));
    }
    else
        program->addShader(new osg::Shader(osg::Shader::FRAGMENT, skinningShaderSource(key, osg::Shader::FRAGMENT)));
    if (key.skinning)
    {
        const SkinAttributeSlots slots = skinAttributeSlots(key.profile);
        program->addBindAttribLocation("osgActor_joints", slots.joints);
        program->addBindAttribLocation("osgActor_weights", slots.weights);
        if (key.influences == 8) program->addBindAttribLocation("osgActor_weights1", slots.weights1);
    }
    return program;
}

namespace {

/** The shared state sets, made on first use. Never destroyed: a program's destructor at exit would schedule GL
  * deletions in OSG's context data, itself a static whose destruction order is unknown. */
struct ProgramStateSets
{
    struct Entry
    {
        osg::ref_ptr<osg::StateSet> stateSet;
        // Kept, so that no other program takes its address (the key's) while the entry lives.
        osg::ref_ptr<const osg::Program> fragmentProgram;
    };
    std::mutex mutex;
    std::map<SkinningProgramKey, Entry> byKey;
};

ProgramStateSets& programStateSets()
{
    static ProgramStateSets* const sets = new ProgramStateSets;
    return *sets;
}

} // namespace

void releaseSkinningProgramsGLObjects(osg::State* state)
{
    ProgramStateSets& sets = programStateSets();
    std::lock_guard<std::mutex> lock(sets.mutex);
    for (auto& entry : sets.byKey) entry.second.stateSet->releaseGLObjects(state);
}

void resizeSkinningProgramsGLObjectBuffers(unsigned maxSize)
{
    ProgramStateSets& sets = programStateSets();
    std::lock_guard<std::mutex> lock(sets.mutex);
    for (auto& entry : sets.byKey) entry.second.stateSet->resizeGLObjectBuffers(maxSize);
}

osg::StateSet* getSkinningProgramStateSet(const SkinningProgramKey& given)
{
    ProgramStateSets& sets = programStateSets();
    const SkinningProgramKey key = canonical(given);
    std::lock_guard<std::mutex> lock(sets.mutex);
    ProgramStateSets::Entry& entry = sets.byKey[key];
    osg::ref_ptr<osg::StateSet>& stateSet = entry.stateSet;
    if (!stateSet)
    {
        entry.fragmentProgram = key.fragmentProgram;
        stateSet = new osg::StateSet;
        stateSet->setAttribute(createSkinningProgram(key).get());
        const char* sampler = key.instancing == SkinInstancing::PerInstance ? "osgActor_instances" : "osgActor_palette";
        if (key.skinning && key.palette == SkinPaletteStorage::TextureBuffer)
            stateSet->addUniform(new osg::Uniform(sampler, static_cast<int>(kSkinPaletteTextureUnit)));
    }
    return stateSet.get();
}

} // namespace osgActor
