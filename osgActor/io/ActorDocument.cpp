#include <osgActor/io/ActorDocument>

#include "../core/detail/EnumNames.h"

namespace osgActor {

namespace {

// The .actor words of each enum, in the enum's order: one table each, read and written alike.
const char* const kKindNames[] = {"box", "sphere", "capsule", "cylinder", "cone", "model"};
const char* const kInterpolationNames[] = {"step", "linear", "cubic"};
const char* const kTranslationModeNames[] = {"after_rotation", "before_rotation"};
const char* const kBoundsNames[] = {"follows_pose", "covers_rotations"}; // false, true
const char* const kCullModeNames[] = {"as_one", "node_by_node"};          // false, true

} // namespace

static_assert(static_cast<int>(Interpolation::Step) == 0 && static_cast<int>(Interpolation::Linear) == 1 &&
                  static_cast<int>(Interpolation::Cubic) == 2,
              "kInterpolationNames follows Interpolation's order");
static_assert(static_cast<int>(TranslationMode::AfterRotation) == 0 &&
                  static_cast<int>(TranslationMode::BeforeRotation) == 1,
              "kTranslationModeNames follows TranslationMode's order");

const char* interpolationName(Interpolation interpolation)
{
    return kInterpolationNames[static_cast<unsigned>(interpolation)];
}

bool parseInterpolation(const std::string& text, Interpolation& interpolation)
{
    return parseEnumName(kInterpolationNames, text, interpolation);
}

const char* translationModeName(TranslationMode mode) { return kTranslationModeNames[static_cast<unsigned>(mode)]; }

bool parseTranslationMode(const std::string& text, TranslationMode& mode)
{
    return parseEnumName(kTranslationModeNames, text, mode);
}

const char* boundsName(bool coverRotations) { return kBoundsNames[coverRotations ? 1 : 0]; }

bool parseBounds(const std::string& text, bool& coverRotations)
{
    return parseEnumName(kBoundsNames, text, coverRotations);
}

const char* cullModeName(bool nodeByNode) { return kCullModeNames[nodeByNode ? 1 : 0]; }

bool parseCullMode(const std::string& text, bool& nodeByNode)
{
    return parseEnumName(kCullModeNames, text, nodeByNode);
}

const char* geometryKindName(GeometryKind kind) { return kKindNames[static_cast<unsigned>(kind)]; }

bool parseShapeKind(const std::string& text, GeometryKind& kind)
{
    for (unsigned i = 0; i < static_cast<unsigned>(GeometryKind::Model); ++i)
    {
        if (text == kKindNames[i])
        {
            kind = static_cast<GeometryKind>(i);
            return true;
        }
    }
    return false;
}

bool isReservedSection(const std::string& keyword) { return keyword == "jointmap"; }

BuildResult buildDefinition(const ActorDocument& document, const std::string& fileName)
{
    // The joints' specs are read where they are, in the document: a copy of each would be a few hundred bytes a
    // joint more to write and read again, which a large actor's read does not keep in the caches.
    const JointSpecList specs(document.joints.empty() ? nullptr : &document.joints.front().spec,
                              document.joints.size(), sizeof(JointDocument));
    BuildResult result = ActorDefinitionBuilder::buildFrom(document.name, specs);
    if (!result)
    {
        // The builder's joint index is the document's.
        const int line = result.errorJoint >= 0 ? document.joints[static_cast<unsigned>(result.errorJoint)].line
                                                : document.line;
        result.error = fileName + ":" + std::to_string(line) + ": " + result.error;
    }
    return result;
}

bool buildIkChains(const ActorDocument& document, const ActorDefinition& definition, const std::string& fileName,
                   std::vector<IkChainPtr>& chains, std::string& error)
{
    std::vector<IkChainPtr> built;
    for (const IkChainDocument& chain : document.ikChains)
    {
        const IkChainBuildResult result = buildIkChain(definition, chain.spec);
        if (!result)
        {
            error = fileName + ":" + std::to_string(chain.line) + ": " + result.error;
            chains.clear();
            return false;
        }
        built.push_back(result.chain);
    }
    chains.swap(built);
    return true;
}

ActorDocument makeDocument(const ActorDefinition& definition)
{
    ActorDocument document;
    document.name = definition.getName();
    document.joints.resize(definition.getNumJoints());
    for (unsigned j = 0; j < definition.getNumJoints(); ++j) document.joints[j].spec = toJointSpec(definition, j);
    return document;
}

} // namespace osgActor

