#include <osgActor/mocap/AsfReader>
#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>
#include <osgActor/text/TextLines>

#include <osgActor/core/ActorDefinitionBuilder>

#include <glm/gtc/quaternion.hpp>

#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <unordered_map>

namespace osgActor {

namespace {

/** One bone (or the root) as the ASF file describes it. */
struct AsfBone
{
    std::string name;
    std::string parent;
    glm::dvec3 direction{0.0};
    double length = 0.0;
    glm::dvec3 axisAngles{0.0}; // file angle units, one per letter of axisOrder
    std::string axisOrder = "XYZ";
    std::vector<Dof> dofs;      // in the order the dof (or root order) line lists them
    std::vector<double> mins, maxs; // per listed dof, file angle units
    glm::dvec3 position{0.0};   // root only, file units
    unsigned line = 0;
};

glm::dmat3 axisRotation(unsigned axis, double angle)
{
    const double c = std::cos(angle), s = std::sin(angle);
    glm::dmat3 r(1.0);
    const unsigned i = (axis + 1) % 3, j = (axis + 2) % 3;
    r[i][i] = c;
    r[i][j] = s;
    r[j][i] = -s;
    r[j][j] = c;
    return r;
}

bool isAxisOrder(std::string_view token)
{
    if (token.size() != 3) return false;
    EulerOrder order;
    return parseEulerOrder(std::string(token), order);
}

class AsfParser
{
public:
    AsfParser(std::istream& in, const std::string& fileName, const AsfImportOptions& options)
        : _text(in, fileName), _options(options)
    {
        _result.options = options;
    }
    AsfImport run();

private:
    bool fail(const std::string& message)
    {
        if (_error.empty()) _error = _text.where() + message;
        return false;
    }
    bool nextContentLine();
    bool readVector(const std::vector<std::string_view>& tokens, std::size_t first, glm::dvec3& v, const char* what);
    bool parseUnits();
    bool parseRoot();
    bool parseBone();
    bool parseLimits(AsfBone& bone);
    bool parseHierarchy();
    bool build();

    TextLines _text;
    const AsfImportOptions& _options;
    AsfImport _result;
    AsfBone _root;
    std::vector<AsfBone> _bones;
    std::unordered_map<std::string, unsigned> _boneIndex;
    bool _haveRoot = false;
    bool _haveHierarchy = false;
    std::string _error;
    bool _pending = false; // the current line is a section header not yet handled
};

bool AsfParser::nextContentLine()
{
    while (_text.nextLine())
        if (!_text.tokens().empty() && _text.tokens()[0].front() != '#') return true;
    return false;
}

bool AsfParser::readVector(const std::vector<std::string_view>& tokens, std::size_t first, glm::dvec3& v,
                           const char* what)
{
    if (tokens.size() < first + 3) return fail(std::string(what) + " needs three numbers");
    for (unsigned i = 0; i < 3; ++i)
        if (!parseNumber(tokens[first + i], v[i]))
            return fail(std::string(what) + ": " + numberProblem(tokens[first + i]));
    return true;
}

bool AsfParser::parseUnits()
{
    while (nextContentLine())
    {
        const std::vector<std::string_view>& t = _text.tokens();
        if (t[0].front() == ':')
        {
            _pending = true;
            return true;
        }
        if (t.size() < 2) return fail("a unit needs a value");
        if (sameWord(t[0], "length"))
        {
            if (!parseNumber(t[1], _result.lengthUnit) || !(_result.lengthUnit > 0.0))
                return fail("the length unit must be a positive number");
        }
        else if (sameWord(t[0], "angle"))
        {
            if (sameWord(t[1], "deg")) _result.degrees = true;
            else if (sameWord(t[1], "rad")) _result.degrees = false;
            else return fail("the angle unit must be deg or rad, not '" + std::string(t[1]) + "'");
        }
        // mass and any other unit do not affect kinematics
    }
    return true;
}

bool AsfParser::parseRoot()
{
    _haveRoot = true;
    _root.name = "root";
    _root.line = _text.lineNumber();
    while (nextContentLine())
    {
        const std::vector<std::string_view>& t = _text.tokens();
        if (t[0].front() == ':')
        {
            _pending = true;
            return true;
        }
        if (sameWord(t[0], "order"))
        {
            for (std::size_t i = 1; i < t.size(); ++i)
            {
                // TX TY TZ RX RY RZ, any case.
                const std::string_view token = t[i];
                const char kind =
                    token.empty() ? ' ' : static_cast<char>(std::toupper(static_cast<unsigned char>(token[0])));
                const char axis =
                    token.size() != 2 ? ' ' : static_cast<char>(std::toupper(static_cast<unsigned char>(token[1])));
                if ((kind != 'T' && kind != 'R') || axis < 'X' || axis > 'Z')
                    return fail("unknown root order token '" + std::string(token) + "'");
                const Dof dof = static_cast<Dof>((kind == 'T' ? 3 : 0) + (axis - 'X'));
                for (Dof seen : _root.dofs)
                    if (seen == dof) return fail("the root order lists '" + std::string(token) + "' twice");
                _root.dofs.push_back(dof);
            }
        }
        else if (sameWord(t[0], "axis"))
        {
            if (t.size() < 2 || !isAxisOrder(t[1])) return fail("the root axis must be an order like XYZ");
            _root.axisOrder = std::string(t[1]);
        }
        else if (sameWord(t[0], "position"))
        {
            if (!readVector(t, 1, _root.position, "the root position")) return false;
        }
        else if (sameWord(t[0], "orientation"))
        {
            if (!readVector(t, 1, _root.axisAngles, "the root orientation")) return false;
        }
        else
            return fail("unknown root keyword '" + std::string(t[0]) + "'");
    }
    return true;
}

bool AsfParser::parseLimits(AsfBone& bone)
{
    // "limits (-160.0 20.0)" then one "(min max)" per further dof, possibly on following lines.
    std::vector<double> numbers;
    bool firstLine = true;
    while (numbers.size() < 2 * bone.dofs.size())
    {
        if (!firstLine && !nextContentLine()) return fail("the file ends inside the limits of '" + bone.name + "'");
        std::string cleaned(_text.line());
        for (char& c : cleaned)
            if (c == '(' || c == ')') c = ' ';
        std::size_t i = 0;
        unsigned tokenNumber = 0;
        while (i < cleaned.size())
        {
            while (i < cleaned.size() && isBlank(cleaned[i])) ++i;
            const std::size_t start = i;
            while (i < cleaned.size() && !isBlank(cleaned[i])) ++i;
            if (i == start) break;
            const std::string_view token(cleaned.data() + start, i - start);
            if (firstLine && tokenNumber++ == 0) continue; // the word "limits"
            double value;
            if (sameWord(token, "inf") || sameWord(token, "+inf")) value = std::numeric_limits<double>::infinity();
            else if (sameWord(token, "-inf")) value = -std::numeric_limits<double>::infinity();
            else if (!parseNumber(token, value))
                return fail("a limit of '" + bone.name + "': " + numberProblem(token));
            numbers.push_back(value);
        }
        firstLine = false;
    }
    if (numbers.size() != 2 * bone.dofs.size())
        return fail("'" + bone.name + "' has " + std::to_string(numbers.size()) + " limit values for " +
                    std::to_string(bone.dofs.size()) + " dofs");
    for (std::size_t d = 0; d < bone.dofs.size(); ++d)
    {
        bone.mins[d] = numbers[2 * d];
        bone.maxs[d] = numbers[2 * d + 1];
        if (bone.mins[d] > bone.maxs[d])
            return fail("a limit of '" + bone.name + "' has its minimum above its maximum");
    }
    return true;
}

bool AsfParser::parseBone()
{
    AsfBone bone;
    bone.line = _text.lineNumber();
    while (nextContentLine())
    {
        const std::vector<std::string_view>& t = _text.tokens();
        if (sameWord(t[0], "end"))
        {
            if (bone.name.empty()) return fail("a bone has no name");
            if (bone.name == "root" || !_boneIndex.emplace(bone.name, static_cast<unsigned>(_bones.size())).second)
                return fail("a second bone is named '" + bone.name + "'");
            _bones.push_back(bone);
            return true;
        }
        if (sameWord(t[0], "name"))
        {
            if (t.size() < 2) return fail("a bone name is missing");
            bone.name = std::string(t[1]);
        }
        else if (sameWord(t[0], "direction"))
        {
            if (!readVector(t, 1, bone.direction, "the direction")) return false;
        }
        else if (sameWord(t[0], "length"))
        {
            if (t.size() < 2 || !parseNumber(t[1], bone.length) || bone.length < 0.0)
                return fail("the length of '" + bone.name + "' must be a number >= 0");
        }
        else if (sameWord(t[0], "axis"))
        {
            if (!readVector(t, 1, bone.axisAngles, "the axis")) return false;
            if (t.size() < 5 || !isAxisOrder(t[4]))
                return fail("the axis of '" + bone.name + "' needs an order like XYZ");
            bone.axisOrder = std::string(t[4]);
        }
        else if (sameWord(t[0], "dof"))
        {
            for (std::size_t i = 1; i < t.size(); ++i)
            {
                Dof dof;
                if (sameWord(t[i], "l"))
                    return fail("dof 'l' (stretching) of '" + bone.name +
                                "' is not supported (bones take rx, ry, rz, tx, ty, tz)");
                if (!parseDof(std::string(t[i]), dof))
                    return fail("dof '" + std::string(t[i]) + "' of '" + bone.name +
                                "' is not supported (bones take rx, ry, rz, tx, ty, tz)");
                for (Dof seen : bone.dofs)
                    if (seen == dof) return fail("'" + bone.name + "' lists dof '" + std::string(t[i]) + "' twice");
                bone.dofs.push_back(dof);
            }
            bone.mins.assign(bone.dofs.size(), -std::numeric_limits<double>::infinity());
            bone.maxs.assign(bone.dofs.size(), std::numeric_limits<double>::infinity());
        }
        else if (sameWord(t[0], "limits"))
        {
            if (!parseLimits(bone)) return false;
        }
        else if (!sameWord(t[0], "id") && !sameWord(t[0], "bodymass") && !sameWord(t[0], "cofmass"))
            return fail("unknown bone keyword '" + std::string(t[0]) + "'");
    }
    return fail("the file ends inside bone '" + bone.name + "' (missing 'end')");
}

bool AsfParser::parseHierarchy()
{
    _haveHierarchy = true;
    while (nextContentLine())
    {
        const std::vector<std::string_view>& t = _text.tokens();
        if (sameWord(t[0], "begin")) continue;
        if (sameWord(t[0], "end")) return true;
        const std::string parent(t[0]);
        if (parent != "root" && !_boneIndex.count(parent)) return fail("unknown bone '" + parent + "' in :hierarchy");
        for (std::size_t i = 1; i < t.size(); ++i)
        {
            const auto child = _boneIndex.find(std::string(t[i]));
            if (child == _boneIndex.end()) return fail("unknown bone '" + std::string(t[i]) + "' in :hierarchy");
            if (!_bones[child->second].parent.empty())
                return fail("bone '" + child->first + "' has a second parent in :hierarchy");
            _bones[child->second].parent = parent;
        }
    }
    return fail("the file ends inside :hierarchy (missing 'end')");
}

bool AsfParser::build()
{
    const double angle = _result.degrees ? kRadiansPerDegree : 1.0; // radiansFromDegrees()
    const double scale = _options.scale;
    ActorDefinitionBuilder builder(_options.name.empty() ? baseNameOf(_text.fileName()) : _options.name);
    auto axisOf = [&](const AsfBone& bone) { return asfAxisRotation(bone.axisAngles * angle, bone.axisOrder); };
    auto addDofs = [&](ActorDefinitionBuilder::JointRef& ref, const AsfBone& bone) {
        DofMask mask = 0;
        unsigned axes[3];
        unsigned numRotations = 0;
        // First listed applied first: the product lists the rotations in reverse.
        for (auto it = bone.dofs.rbegin(); it != bone.dofs.rend(); ++it)
            if (isRotation(*it)) axes[numRotations++] = osgActor::axisOf(*it);
        for (Dof dof : bone.dofs) mask = static_cast<DofMask>(mask | dofBit(dof));
        ref.dofs(mask).translationMode(TranslationMode::BeforeRotation);
        EulerOrder order = EulerOrder::XYZ;
        if (!eulerOrderForAxes(axes, numRotations, order)) return fail("'" + bone.name + "' repeats a rotation");
        ref.eulerOrder(order);
        if (!_options.applyLimits || bone.mins.empty()) return true;
        for (std::size_t d = 0; d < bone.dofs.size(); ++d)
        {
            const double unit = isRotation(bone.dofs[d]) ? angle : scale; // translations are lengths
            const double lo = bone.mins[d] * unit, hi = bone.maxs[d] * unit;
            ref.limits(bone.dofs[d], lo, hi);
            ref.defaultValue(bone.dofs[d], std::min(std::max(0.0, lo), hi)); // rest pose within the limits
        }
        return true;
    };

    const glm::dquat toZUp = _options.convertToZUp ? upAxisToZUp(_options.fileUpAxis) : glm::dquat(1, 0, 0, 0);
    const glm::dmat3 rootAxis = axisOf(_root);
    ActorDefinitionBuilder::JointRef rootRef = builder.addJoint("root");
    rootRef.offset(toZUp * (_root.position * scale)).rotation(toZUp * glm::quat_cast(rootAxis));
    if (!addDofs(rootRef, _root)) return false;
    unsigned numRootTranslations = 0;
    for (Dof dof : _root.dofs) numRootTranslations += isRotation(dof) ? 0 : 1;
    if (numRootTranslations != 0 && numRootTranslations != 3 && rootAxis != glm::dmat3(1.0))
        return fail("a rotated root axis needs all of TX TY TZ or none");
    const glm::dmat3 rootTranslationMap = glm::transpose(rootAxis) * scale;

    for (const AsfBone& bone : _bones)
    {
        if (bone.parent.empty())
        {
            _error = _text.where(bone.line) + "bone '" + bone.name + "' is not in :hierarchy";
            return false;
        }
        const bool belowRoot = bone.parent == "root";
        const AsfBone& parent = belowRoot ? _root : _bones[_boneIndex[bone.parent]];
        const glm::dmat3 parentAxisInverse = glm::transpose(axisOf(parent));
        // The bone starts where its parent ends: in the parent joint's frame (W(p) C_p) that is C_p^-1 l_p d_p.
        const glm::dvec3 start =
            belowRoot ? glm::dvec3(0.0) : parentAxisInverse * (parent.direction * parent.length * scale);
        ActorDefinitionBuilder::JointRef ref = builder.addJoint(bone.name, bone.parent);
        ref.offset(start).rotation(glm::quat_cast(parentAxisInverse * axisOf(bone)));
        if (!addDofs(ref, bone)) return false;
    }
    const BuildResult built = builder.build();
    if (!built)
    {
        // The builder's joints are the root and then the bones, in file order: its index names the joint's line.
        const int joint = built.errorJoint;
        const unsigned line = joint == 0 ? _root.line : joint > 0 ? _bones[static_cast<unsigned>(joint - 1)].line : 0;
        _error = (line > 0 ? _text.where(line) : _text.fileName() + ": ") + built.error;
        return false;
    }
    _result.definition = built.definition;

    auto addLayout = [&](const AsfBone& bone, const glm::dmat3& translationMap) {
        if (bone.dofs.empty()) return;
        AsfAmcLayout layout;
        layout.bone = bone.name;
        layout.translationMap = translationMap;
        const unsigned joint = static_cast<unsigned>(built.definition->findJoint(bone.name));
        for (Dof dof : bone.dofs)
        {
            layout.dofs.push_back(static_cast<unsigned>(built.definition->getDofIndex(joint, dof)));
            layout.angular.push_back(isRotation(dof));
            layout.translationAxis.push_back(isRotation(dof) ? -1 : static_cast<int>(osgActor::axisOf(dof)));
        }
        _result.layouts.push_back(layout);
    };
    addLayout(_root, rootTranslationMap);
    // A bone's translations are already in its axis frame, the frame of its joint.
    for (const AsfBone& bone : _bones) addLayout(bone, glm::dmat3(scale));
    return true;
}

AsfImport AsfParser::run()
{
    bool ok = _text.error().empty();
    _error = _text.error();
    while (ok && (_pending || nextContentLine()))
    {
        _pending = false;
        const std::vector<std::string_view>& t = _text.tokens();
        if (t[0].front() != ':') ok = fail("expected a section such as :root, found '" + std::string(t[0]) + "'");
        else if (sameWord(t[0], ":units")) ok = parseUnits();
        else if (sameWord(t[0], ":root")) ok = parseRoot();
        else if (sameWord(t[0], ":bonedata"))
        {
            while (ok && nextContentLine())
            {
                if (_text.tokens()[0].front() == ':')
                {
                    _pending = true;
                    break;
                }
                if (sameWord(_text.tokens()[0], "begin")) ok = parseBone();
                else ok = fail("expected 'begin' in :bonedata, found '" + std::string(_text.tokens()[0]) + "'");
            }
        }
        else if (sameWord(t[0], ":hierarchy")) ok = parseHierarchy();
        else
        {
            // :version, :name, :documentation and others: skip their lines.
            while (nextContentLine())
                if (_text.tokens()[0].front() == ':')
                {
                    _pending = true;
                    break;
                }
        }
    }
    if (ok && !_haveRoot) ok = fail("the file has no :root section");
    if (ok && !_haveHierarchy) ok = fail("the file has no :hierarchy section");
    ok = ok && build();
    if (!ok)
    {
        AsfImport failed;
        failed.error = _error;
        return failed;
    }
    return _result;
}

} // namespace

glm::dmat3 asfAxisRotation(const glm::dvec3& angles, const std::string& order)
{
    glm::dmat3 m(1.0);
    for (std::size_t i = 0; i < order.size() && i < 3; ++i)
    {
        const unsigned axis = static_cast<unsigned>(std::toupper(static_cast<unsigned char>(order[i])) - 'X');
        m = axisRotation(axis, angles[static_cast<glm::length_t>(i)]) * m; // first letter applied first
    }
    return m;
}

AsfImport readAsf(std::istream& in, const std::string& fileName, const AsfImportOptions& options)
{
    AsfParser parser(in, fileName, options);
    return parser.run();
}

AsfImport readAsfFile(const std::string& path, const AsfImportOptions& options)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        AsfImport failed;
        failed.error = path + ": cannot open the file";
        return failed;
    }
    return readAsf(in, path, options);
}

} // namespace osgActor
