#include <osgActor/mocap/BvhReader>
#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>
#include <osgActor/text/TextLines>

#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/ClipBuilder>

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <unordered_set>

namespace osgActor {

namespace {

/** A clip counts its frames in an unsigned int. */
constexpr unsigned long kMaxFrames = 4294967295ul;
/** Deepest joint nesting read (real skeletons: a few dozen; the .actor syntax allows 200 too). */
constexpr unsigned kMaxDepth = 200;

/** A BVH joint as read from the hierarchy, in file order (parents first). */
struct BvhJoint
{
    std::string name;
    int parent = -1;
    glm::dvec3 offset{0.0};
    /** Dof per channel, in the file's column order. */
    std::vector<Dof> channels;
    bool endSite = false;
    unsigned line = 0;
};

class BvhParser
{
public:
    BvhParser(std::istream& in, const std::string& fileName, const BvhImportOptions& options)
        : _text(in, fileName), _options(options)
    {
    }

    MocapImport run();

private:
    bool fail(const std::string& message)
    {
        if (_error.empty()) _error = _text.where() + message;
        return false;
    }
    bool expect(std::string_view keyword);
    bool readNumber(double& value, const char* what);
    bool parseJoint(int parent, bool endSite, unsigned depth);
    bool parseChannels(BvhJoint& joint);
    bool parseMotionHeader(unsigned long& numFrames, double& frameTime);
    bool buildDefinition(MocapImport& result);
    bool readFrames(MocapImport& result, unsigned long numFrames, double frameTime);

    TextLines _text;
    const BvhImportOptions& _options;
    std::vector<BvhJoint> _joints;
    std::string _error;
    unsigned _numChannels = 0;
};

bool BvhParser::expect(std::string_view keyword)
{
    std::string_view token;
    if (!_text.nextToken(token)) return fail("the file ends where '" + std::string(keyword) + "' was expected");
    if (!sameWord(token, keyword))
        return fail("expected '" + std::string(keyword) + "', found '" + std::string(token) + "'");
    return true;
}

bool BvhParser::readNumber(double& value, const char* what)
{
    std::string_view token;
    if (!_text.nextToken(token)) return fail(std::string("the file ends where ") + what + " was expected");
    if (!parseNumber(token, value))
        return fail(std::string("expected ") + what + ": " + numberProblem(token));
    return true;
}

bool BvhParser::parseChannels(BvhJoint& joint)
{
    double count = 0.0;
    if (!readNumber(count, "a channel count")) return false;
    if (count < 0 || count > 6 || count != static_cast<int>(count))
        return fail("joint '" + joint.name + "' declares " + std::to_string(count) + " channels; 0 to 6 allowed");
    joint.channels.clear();
    for (int c = 0; c < static_cast<int>(count); ++c)
    {
        std::string_view token;
        if (!_text.nextToken(token)) return fail("the file ends inside a CHANNELS list");
        static const char* const kNames[6] = {"Xrotation", "Yrotation", "Zrotation",
                                             "Xposition", "Yposition", "Zposition"};
        int found = -1;
        for (int k = 0; k < 6; ++k)
            if (sameWord(token, kNames[k])) found = k;
        if (found < 0) return fail("unknown channel '" + std::string(token) + "' on joint '" + joint.name + "'");
        const Dof dof = static_cast<Dof>(found);
        for (Dof seen : joint.channels)
            if (seen == dof) return fail("joint '" + joint.name + "' lists channel '" + std::string(token) + "' twice");
        joint.channels.push_back(dof);
    }
    _numChannels += static_cast<unsigned>(joint.channels.size());
    return true;
}

bool BvhParser::parseJoint(int parent, bool endSite, unsigned depth)
{
    // Joints nest by recursion: a bound keeps a hostile file from overflowing the stack (docs/robustness.md).
    if (depth > kMaxDepth) return fail("joints are nested more than " + std::to_string(kMaxDepth) + " deep");
    BvhJoint joint;
    joint.parent = parent;
    joint.endSite = endSite;
    joint.line = _text.lineNumber();
    if (endSite)
    {
        _text.skipRestOfLine(); // "Site"
        joint.name = _joints[static_cast<unsigned>(parent)].name + "_end";
    }
    else
    {
        joint.name = _text.restOfLine();
        if (joint.name.empty()) return fail("a joint has no name");
    }
    if (!expect("{")) return false;
    const unsigned index = static_cast<unsigned>(_joints.size());
    _joints.push_back(joint);
    bool hasOffset = false;
    std::string_view token;
    while (_text.nextToken(token))
    {
        if (sameWord(token, "OFFSET"))
        {
            glm::dvec3 offset;
            if (!readNumber(offset.x, "an OFFSET value") || !readNumber(offset.y, "an OFFSET value") ||
                !readNumber(offset.z, "an OFFSET value"))
                return false;
            _joints[index].offset = offset;
            hasOffset = true;
        }
        else if (sameWord(token, "CHANNELS") && !endSite)
        {
            if (!parseChannels(_joints[index])) return false;
        }
        else if (sameWord(token, "JOINT") && !endSite)
        {
            if (!parseJoint(static_cast<int>(index), false, depth + 1)) return false;
        }
        else if (sameWord(token, "End") && !endSite)
        {
            if (!parseJoint(static_cast<int>(index), true, depth + 1)) return false;
        }
        else if (token == "}")
        {
            if (!hasOffset) return fail("'" + _joints[index].name + "' has no OFFSET");
            return true;
        }
        else
            return fail("unexpected '" + std::string(token) + "' in '" + _joints[index].name + "'");
    }
    return fail("the file ends inside joint '" + _joints[index].name + "' (missing '}')");
}

bool BvhParser::parseMotionHeader(unsigned long& numFrames, double& frameTime)
{
    if (!expect("Frames:")) return false;
    double frames = 0.0;
    if (!readNumber(frames, "the frame count")) return false;
    // Range first: converting a double beyond unsigned long is undefined (docs/robustness.md).
    if (!(frames >= 0 && frames <= kMaxFrames) || frames != std::floor(frames))
        return fail("the frame count must be a whole number from 0 to " + std::to_string(kMaxFrames));
    numFrames = static_cast<unsigned long>(frames);
    if (!expect("Frame") || !expect("Time:") || !readNumber(frameTime, "the frame time")) return false;
    if (!(frameTime > 0.0)) return fail("the frame time must be positive");
    _text.skipRestOfLine();
    return true;
}

bool BvhParser::buildDefinition(MocapImport& result)
{
    ActorDefinitionBuilder builder(_options.name.empty() ? baseNameOf(_text.fileName()) : _options.name);
    const glm::dquat toZUp = _options.convertToZUp ? upAxisToZUp(_options.fileUpAxis) : glm::dquat(1, 0, 0, 0);
    std::unordered_set<std::string> names;
    for (const BvhJoint& joint : _joints)
        if (!joint.endSite) names.insert(joint.name);
    // An End Site is named after its parent; should a real joint already have that name, it takes the next free one.
    for (BvhJoint& joint : _joints)
        if (joint.endSite && _options.endSitesAsJoints)
            while (!names.insert(joint.name).second) joint.name += "_";
    names.clear();
    for (const BvhJoint& joint : _joints)
    {
        if (joint.endSite && !_options.endSitesAsJoints) continue;
        if (!names.insert(joint.name).second)
        {
            _error = _text.where(joint.line) + "a second joint is named '" + joint.name + "'";
            return false;
        }
        const bool root = joint.parent < 0;
        glm::dvec3 offset = joint.offset * _options.scale;
        if (root && _options.absoluteRootPosition) offset = glm::dvec3(0.0);
        ActorDefinitionBuilder::JointRef ref =
            builder.addJoint(joint.name, root ? std::string() : _joints[static_cast<unsigned>(joint.parent)].name);
        // The up-axis change sits on each root: L = Rup * T(OFFSET + p) * R = T(Rup OFFSET) * Rup * T(p) * R.
        ref.offset(root ? toZUp * offset : offset).rotation(root ? toZUp : glm::dquat(1, 0, 0, 0));
        ref.translationMode(TranslationMode::BeforeRotation);

        DofMask mask = 0;
        unsigned axes[3];
        unsigned numRotations = 0;
        for (Dof dof : joint.channels)
        {
            mask = static_cast<DofMask>(mask | dofBit(dof));
            if (isRotation(dof)) axes[numRotations++] = axisOf(dof);
        }
        ref.dofs(mask);
        EulerOrder order = EulerOrder::XYZ;
        eulerOrderForAxes(axes, numRotations, order); // cannot fail: parseChannels refused repeats
        ref.eulerOrder(order);
    }
    const BuildResult built = builder.build();
    if (!built)
    {
        // The builder's joints are those added above, in file order: its index names the joint's line.
        unsigned line = 0;
        for (std::size_t j = 0, added = 0; j < _joints.size() && built.errorJoint >= 0; ++j)
            if (!_joints[j].endSite || _options.endSitesAsJoints)
                if (static_cast<int>(added++) == built.errorJoint) line = _joints[j].line;
        _error = (line > 0 ? _text.where(line) : _text.fileName() + ": ") + built.error;
        return false;
    }
    result.definition = built.definition;
    return true;
}

bool BvhParser::readFrames(MocapImport& result, unsigned long numFrames, double frameTime)
{
    const ActorDefinition& def = *result.definition;
    // Where each file column goes in a frame (the DOF index) and the factor that converts it.
    std::vector<unsigned> columnDof;
    std::vector<double> columnFactor;
    for (const BvhJoint& joint : _joints)
    {
        if (joint.endSite) continue;
        const unsigned j = static_cast<unsigned>(def.findJoint(joint.name));
        for (Dof dof : joint.channels)
        {
            columnDof.push_back(static_cast<unsigned>(def.getDofIndex(j, dof)));
            columnFactor.push_back(isRotation(dof) ? kRadiansPerDegree : _options.scale); // radiansFromDegrees()
        }
    }
    const unsigned numChannels = def.getNumDofs();
    std::vector<double> values;
    // The header's count is a hint, not a promise: a lying one must not allocate gigabytes before any frame is read.
    // A frame's line holds numChannels numbers and the blanks between them, two bytes a channel at the least, so
    // the text left bounds the frames it may hold; room for those is made at once (grown frame by frame, a long
    // motion's values would be copied, and mapped afresh, each time they fill).
    const unsigned long framesTheTextMayHold =
        numChannels == 0 ? 0ul : static_cast<unsigned long>(_text.bytesAfterLine() / (2ul * numChannels) + 1ul);
    values.reserve(std::min(numFrames, framesTheTextMayHold) * numChannels);
    unsigned long frame = 0;
    unsigned long extraLines = 0;
    while (_text.nextLine())
    {
        const std::vector<std::string_view>& tokens = _text.tokens();
        if (tokens.empty()) continue;
        if (frame >= numFrames)
        {
            ++extraLines;
            continue;
        }
        if (tokens.size() != numChannels)
            return fail("frame " + std::to_string(frame) + " has " + std::to_string(tokens.size()) +
                        " values; the hierarchy declares " + std::to_string(numChannels) + " channels");
        values.resize(values.size() + numChannels);
        double* row = values.data() + values.size() - numChannels;
        for (unsigned c = 0; c < numChannels; ++c)
        {
            double value;
            if (!parseNumber(tokens[c], value))
                return fail("value " + std::to_string(c + 1) + " of frame " + std::to_string(frame) + ": " +
                            numberProblem(tokens[c]));
            row[columnDof[c]] = value * columnFactor[c];
        }
        ++frame;
    }
    if (extraLines > 0)
        result.warnings.push_back(_text.fileName() + ": " + std::to_string(extraLines) +
                                  " data lines beyond the header's Frames: " + std::to_string(numFrames) +
                                  " were ignored");
    if (frame < numFrames)
        result.warnings.push_back(_text.fileName() + ": the header declares " + std::to_string(numFrames) +
                                  " frames but the file holds " + std::to_string(frame) + "; kept those");
    if (frame == 0 || numChannels == 0) return true; // a skeleton without motion
    if (_options.dropFirstFrame && frame > 1) values.erase(values.begin(), values.begin() + numChannels);

    ClipBuilder clip(def.getName());
    for (unsigned d = 0; d < numChannels; ++d) clip.addChannel(def.getDofName(d), _options.interpolation);
    clip.setFrames(1.0 / frameTime, std::move(values));
    const ClipBuildResult built = clip.build();
    if (!built)
    {
        _error = _text.fileName() + ": " + built.error;
        return false;
    }
    result.clip = built.clip;
    return true;
}

MocapImport BvhParser::run()
{
    MocapImport result;
    if (!_text.error().empty())
    {
        result.error = _text.error();
        return result;
    }
    std::string_view token;
    bool ok = expect("HIERARCHY");
    while (ok && _text.nextToken(token) && !sameWord(token, "MOTION"))
    {
        if (sameWord(token, "ROOT")) ok = parseJoint(-1, false, 0);
        else ok = fail("expected ROOT or MOTION, found '" + std::string(token) + "'");
    }
    if (ok && _joints.empty()) ok = fail("the file has no ROOT joint");
    if (ok && !sameWord(token, "MOTION")) ok = fail("the file ends before its MOTION section");
    unsigned long numFrames = 0;
    double frameTime = 0.0;
    ok = ok && parseMotionHeader(numFrames, frameTime) && buildDefinition(result) &&
         readFrames(result, numFrames, frameTime);
    if (!ok)
    {
        MocapImport failed;
        failed.error = _error;
        return failed;
    }
    return result;
}

} // namespace

MocapImport readBvh(std::istream& in, const std::string& fileName, const BvhImportOptions& options)
{
    BvhParser parser(in, fileName, options);
    return parser.run();
}

MocapImport readBvhFile(const std::string& path, const BvhImportOptions& options)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        MocapImport failed;
        failed.error = path + ": cannot open the file";
        return failed;
    }
    return readBvh(in, path, options);
}

} // namespace osgActor
