#include <osgActor/core/ClipBuilder>
#include <osgActor/io/ActorReader>
#include <osgActor/io/AngleAxis>
#include <osgActor/io/JointMapSection>
#include <osgActor/mocap/MotionFile>
#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <string_view>

namespace osgActor {

namespace {

/** The keywords (or DOF attributes) a block has given so far, to refuse the second of a kind. A block names a few,
  * so they sit in place, not in a heap-allocated set for each of the thousands of joints a file may hold; the views
  * point into the statements being read. */
class SeenWords
{
public:
    /** False when the word was seen already. */
    bool insert(std::string_view word)
    {
        if (count(word)) return false;
        if (_size < _inPlace.size()) _inPlace[_size++] = word;
        else _more.push_back(word);
        return true;
    }

    bool count(std::string_view word) const
    {
        return std::find(_inPlace.begin(), _inPlace.begin() + _size, word) != _inPlace.begin() + _size ||
               std::find(_more.begin(), _more.end(), word) != _more.end();
    }

private:
    std::array<std::string_view, 16> _inPlace;
    std::size_t _size = 0;
    std::vector<std::string_view> _more; // beyond 16: no block of the format has that many keywords
};

// Angles are read by readAngle(): degrees (radiansFromDegrees(), the conversion the writer inverts) or radians with
// the suffix "rad".

/** One read of one file: turns the statements into a document, stopping at the first error. */
class DocumentReader
{
public:
    explicit DocumentReader(const std::string& fileName) : _fileName(fileName) {}

    bool readFile(const std::vector<SyntaxStatement>& statements, ActorDocument& document)
    {
        if (statements.empty() || statements.front().keyword != "osgactor")
            return fail(statements.empty() ? 1 : statements.front().line,
                        "the file must start with the header 'osgactor " +
                            std::to_string(ActorDocument::kFormatVersion) + "'");
        if (!readHeader(statements.front())) return false;
        const SyntaxStatement* actor = nullptr;
        for (std::size_t i = 1; i < statements.size(); ++i)
        {
            const SyntaxStatement& statement = statements[i];
            if (statement.keyword != "actor") return unknownKeyword(statement, "at the top of the file");
            if (actor) return fail(statement.line, "a file holds one actor; the first is at line " +
                                                       std::to_string(actor->line));
            actor = &statement;
        }
        if (!actor) return fail(statements.back().line, "the file has no 'actor' block");
        return readActorBlock(*actor, document);
    }

    const std::string& error() const { return _error; }

    /** The statements of an actor's motion alone (readActorMotion()): motion sections, and how the views treat the
      * actor (isViewingStatement()), which OSG's formats keep with the motion. */
    bool readMotionFile(const std::vector<SyntaxStatement>& statements, ActorDocument& document)
    {
        SeenWords seen;
        for (const SyntaxStatement& s : statements)
        {
            if (isViewingStatement(s.keyword))
            {
                if (!readViewingStatement(seen, s, document)) return false;
                continue;
            }
            if (!isMotionSection(s.keyword)) return unknownKeyword(s, "in an actor's motion");
            if (!readMotionSection(s, document)) return false;
        }
        return true;
    }

    /** The clips of the actor block, after readFile() and once the definition is built. */
    bool readClips(const ActorDefinition& definition, ActorDocument& document)
    {
        std::set<std::string> names;
        for (const SyntaxStatement* statement : _clipStatements)
        {
            ClipDocument clip;
            clip.line = statement->line;
            if (!readClip(*statement, definition, clip)) return false;
            if (!names.insert(clip.name()).second)
                return fail(statement->line, "clip '" + clip.name() + "' is given twice");
            document.clips.push_back(clip);
        }
        return true;
    }

    /** The players of the actor block, after readClips(). */
    bool readPlayers(const ActorDefinition& definition, ActorDocument& document)
    {
        for (const SyntaxStatement* statement : _playerStatements)
        {
            PlayerDocument player;
            if (!readPlayer(*statement, definition, document, player)) return false;
            document.players.push_back(std::move(player));
        }
        return true;
    }

private:
    // --- messages ---

    bool fail(int line, const std::string& message)
    {
        _error = _fileName + ":" + std::to_string(line) + ": " + message;
        return false;
    }

    bool unknownKeyword(const SyntaxStatement& statement, const std::string& where)
    {
        return fail(statement.line, "unknown keyword '" + statement.keyword + "' " + where);
    }

    // --- shape of a statement ---

    bool expectArguments(const SyntaxStatement& statement, std::size_t count)
    {
        if (statement.arguments.size() == count) return true;
        return fail(statement.line, "'" + statement.keyword + "' takes " + std::to_string(count) + " value" +
                                        (count == 1 ? "" : "s") + ", not " +
                                        std::to_string(statement.arguments.size()));
    }

    bool expectNoBlock(const SyntaxStatement& statement)
    {
        if (!statement.hasBlock) return true;
        return fail(statement.line, "'" + statement.keyword + "' takes no block");
    }

    /** Marks a keyword seen in one block; false (with an error) the second time. */
    bool once(SeenWords& seen, const SyntaxStatement& statement)
    {
        if (seen.insert(statement.keyword)) return true;
        return fail(statement.line, "'" + statement.keyword + "' is given twice");
    }

    bool number(const SyntaxArgument& argument, double& value)
    {
        if (argument.quoted) return fail(argument.line, "\"" + argument.text + "\" is a string, not a number");
        if (parseNumber(argument.text, value)) return true;
        return fail(argument.line, numberProblem(argument.text));
    }

    /** An angle (degrees, or radians with the suffix "rad") as radians. */
    bool angle(const SyntaxArgument& argument, double& radians)
    {
        if (argument.quoted) return fail(argument.line, "\"" + argument.text + "\" is a string, not an angle");
        if (readAngle(argument.text, radians) == NumberWord::Finite) return true;
        return fail(argument.line, angleProblem(argument.text));
    }

    /** A value of a DOF or a clip channel: an angle for a rotation, a length otherwise. */
    bool dofValue(const SyntaxArgument& argument, bool angular, double& value)
    {
        return angular ? angle(argument, value) : number(argument, value);
    }

    /** A statement without values or block that sets a flag ("hidden", "blocked"). */
    bool flag(SeenWords& seen, const SyntaxStatement& statement, bool& value)
    {
        if (!once(seen, statement) || !expectNoBlock(statement) || !expectArguments(statement, 0)) return false;
        value = true;
        return true;
    }

    /** A statement of exactly count numbers, without block. */
    bool numbers(const SyntaxStatement& statement, std::size_t count, double* values)
    {
        if (!expectNoBlock(statement) || !expectArguments(statement, count)) return false;
        for (std::size_t i = 0; i < count; ++i)
            if (!number(statement.arguments[i], values[i])) return false;
        return true;
    }

    bool vector3(const SyntaxStatement& statement, glm::dvec3& value)
    {
        double v[3];
        if (!numbers(statement, 3, v)) return false;
        value = glm::dvec3(v[0], v[1], v[2]);
        return true;
    }

    /** A translation an actor holds: within +-kMaxDofMagnitude, as ActorNode's transforms and the offsets. */
    bool translation(const SyntaxStatement& statement, glm::dvec3& value)
    {
        if (!vector3(statement, value)) return false;
        for (int i = 0; i < 3; ++i)
            if (std::abs(value[i]) > kMaxDofMagnitude)
                return fail(statement.line, "'" + statement.keyword + "' " + statement.arguments[i].text +
                                                " lies beyond what an actor holds (+-" +
                                                formatNumber(kMaxDofMagnitude) + ")");
        return true;
    }

    /** "rotation <degrees> <axis x> <axis y> <axis z>", or "rotation quaternion <w> <x> <y> <z>" (what the writer
      * writes where no angle and axis give back exactly the rotation it holds). */
    bool rotation(const SyntaxStatement& statement, glm::dquat& value)
    {
        double v[4];
        if (!statement.arguments.empty() && !statement.arguments.front().quoted &&
            statement.arguments.front().text == "quaternion")
        {
            if (!expectNoBlock(statement) || !expectArguments(statement, 5)) return false;
            for (unsigned i = 0; i < 4; ++i)
                if (!number(statement.arguments[i + 1], v[i])) return false;
            if (quaternionAsWritten(v, value)) return true;
            return fail(statement.line, "the rotation quaternion has no length a double holds (zero or too large)");
        }
        if (!numbers(statement, 4, v)) return false;
        AngleAxis angleAxis;
        angleAxis.degrees = v[0];
        for (unsigned i = 0; i < 3; ++i) angleAxis.axis[i] = v[i + 1];
        if (toQuaternion(angleAxis, value)) return true;
        return fail(statement.line, "the rotation axis is zero, or too long for a double");
    }

    bool positive(const SyntaxStatement& statement, double& value)
    {
        if (!numbers(statement, 1, &value)) return false;
        if (value > 0.0) return true;
        return fail(statement.line, "'" + statement.keyword + "' must be greater than zero");
    }

    bool name(const SyntaxStatement& statement, std::string& value)
    {
        if (!expectArguments(statement, 1)) return false;
        value = statement.arguments.front().text;
        return true;
    }

    // --- the file's parts ---

    bool readHeader(const SyntaxStatement& header)
    {
        double version = 0.0;
        if (!numbers(header, 1, &version)) return false;
        // Range before the whole-number test: converting 1e300 to int is undefined (docs/robustness.md).
        if (!(version >= 1) || version != std::floor(version))
            return fail(header.line, "the format version must be a whole number from 1");
        if (version > ActorDocument::kFormatVersion)
            return fail(header.line, "format version " + header.arguments.front().text +
                                         " is newer than this reader's (" +
                                         std::to_string(ActorDocument::kFormatVersion) + ")");
        return true;
    }

    bool readActorBlock(const SyntaxStatement& actor, ActorDocument& document)
    {
        if (!actor.hasBlock) return fail(actor.line, "'actor' needs a block in braces");
        if (actor.arguments.size() > 1) return expectArguments(actor, 1);
        if (!actor.arguments.empty()) document.name = actor.arguments.front().text;
        document.line = actor.line;
        document.joints.reserve(countJoints(actor.children));
        SeenWords seen;
        for (const SyntaxStatement& s : actor.children)
        {
            const std::string& k = s.keyword;
            bool ok = true;
            if (k == "joint") ok = readJoint(s, std::string(), document);
            else if (k == "pre_translation") ok = once(seen, s) && translation(s, document.preTranslation);
            else if (k == "pre_rotation") ok = once(seen, s) && rotation(s, document.preRotation);
            else if (k == "post_translation") ok = once(seen, s) && translation(s, document.postTranslation);
            else if (k == "post_rotation") ok = once(seen, s) && rotation(s, document.postRotation);
            else if (k == "blocked") ok = flag(seen, s, document.blocked);
            else if (k == "bounds") ok = once(seen, s) && readBounds(s, document.boundsCoverRotations);
            else if (isViewingStatement(k)) ok = readViewingStatement(seen, s, document);
            else if (k == "skin") ok = readSkinFile(s, document);
            else if (isMotionSection(k)) ok = readMotionSection(s, document);
            else if (isReservedSection(k))
            {
                if (!s.hasBlock) return fail(s.line, "'" + k + "' needs a block in braces");
                document.sections.push_back(s);
            }
            else return unknownKeyword(s, "in an actor");
            if (!ok) return false;
        }
        return true;
    }

    /** "skin "file"": a rigged model file whose skins the actor wears (read when the actor is made). */
    bool readSkinFile(const SyntaxStatement& s, ActorDocument& document)
    {
        if (!expectNoBlock(s) || !expectArguments(s, 1)) return false;
        const std::string& file = s.arguments.front().text;
        if (file.empty()) return fail(s.line, "'skin' needs a file name");
        for (const SkinFileDocument& other : document.skinFiles)
            if (other.file == file) return fail(s.line, "skin file '" + file + "' is given twice");
        document.skinFiles.push_back(SkinFileDocument{file, s.line});
        return true;
    }

    /** The sections of an actor block that give its motion rather than its skeleton: clips, trajectories, players
      * and IK chains. */
    static bool isMotionSection(const std::string& keyword)
    {
        return keyword == "clip" || keyword == "player" || keyword == "trajectory" || keyword == "ikchain";
    }

    /** One section isMotionSection() names. Clips and players are only collected here: they are read once the
      * definition is built (readClips(), readPlayers()). */
    bool readMotionSection(const SyntaxStatement& s, ActorDocument& document)
    {
        if (s.keyword == "trajectory") return readTrajectory(s, document);
        if (s.keyword == "ikchain") return readIkChain(s, document);
        if (!s.hasBlock) return fail(s.line, "'" + s.keyword + "' needs a block in braces");
        // Clips are checked against the definition's DOFs; a player names its clip and DOFs, so it comes after them.
        if (s.keyword == "clip") _clipStatements.push_back(&s);
        else _playerStatements.push_back(&s);
        return true;
    }

    /** "trajectory name { [play mode] [paused] [speed s] key time x y z heading ... }", or "file "path.csv""
      * instead of keys (read later, see TrajectoryDocument::file). Headings in degrees. */
    bool readTrajectory(const SyntaxStatement& s, ActorDocument& document)
    {
        if (!s.hasBlock) return fail(s.line, "'trajectory' needs a block in braces");
        if (!expectArguments(s, 1)) return false;
        const std::string& name = s.arguments.front().text;
        for (const TrajectoryDocument& other : document.trajectories)
            if (other.name() == name) return fail(s.line, "trajectory '" + name + "' is given twice");
        TrajectoryDocument trajectory;
        trajectory.line = s.line;
        bool paused = false;
        std::vector<TrajectoryKey> keys;
        SeenWords seen;
        for (const SyntaxStatement& c : s.children)
        {
            const std::string& k = c.keyword;
            bool ok = true;
            if (k == "key")
            {
                // "key time x y z heading": the heading an angle.
                double v[5];
                ok = expectNoBlock(c) && expectArguments(c, 5);
                for (unsigned i = 0; i < 5 && ok; ++i)
                    ok = i < 4 ? number(c.arguments[i], v[i]) : angle(c.arguments[i], v[i]);
                for (unsigned i = 1; i < 4 && ok; ++i)
                    if (std::abs(v[i]) > kMaxDofMagnitude)
                        return fail(c.line, "the key's position " + c.arguments[i].text +
                                                " lies beyond what an actor holds (+-" +
                                                formatNumber(kMaxDofMagnitude) + ")");
                if (ok && !keys.empty() && !(v[0] > keys.back().time))
                    return fail(c.line, "key times must increase (" + c.arguments[0].text + " follows " +
                                            formatNumber(keys.back().time) + ")");
                if (ok) keys.push_back(TrajectoryKey{v[0], glm::dvec3(v[1], v[2], v[3]), v[4]});
            }
            else if (k == "play")
            {
                ok = once(seen, c) && readPlayMode(c, trajectory.playMode);
                trajectory.play = ok;
            }
            else if (k == "paused") ok = flag(seen, c, paused);
            else if (k == "speed") ok = once(seen, c) && numbers(c, 1, &trajectory.speed);
            else if (k == "file")
            {
                ok = once(seen, c) && expectNoBlock(c) && expectArguments(c, 1);
                if (ok) trajectory.file = c.arguments.front().text;
                if (ok && lowerExtensionOf(trajectory.file) != ".csv")
                    return fail(c.line, "'" + trajectory.file + "': a trajectory's file must be CSV (.csv)");
            }
            else return unknownKeyword(c, "in a trajectory");
            if (!ok) return false;
        }
        trajectory.play = trajectory.play && !paused;
        if (!trajectory.file.empty())
        {
            if (!keys.empty())
                return fail(s.line,
                            "trajectory '" + name + "' reads its keys from a file, so it has no keys of its own");
            trajectory.fileTrajectoryName = name;
        }
        else
        {
            if (keys.empty()) return fail(s.line, "trajectory '" + name + "' has no key");
            const TrajectoryBuildResult built = TrajectoryBuilder::build(name, std::move(keys));
            if (!built) return fail(s.line, built.error);
            trajectory.trajectory = built.trajectory;
        }
        document.trajectories.push_back(std::move(trajectory));
        return true;
    }

    /** "ikchain name { root j; effector j; ... }" (docs/ik.md); the chain is checked against the skeleton once the
      * definition is built (buildIkChains). */
    bool readIkChain(const SyntaxStatement& statement, ActorDocument& document)
    {
        if (!statement.hasBlock) return fail(statement.line, "'ikchain' needs a block in braces");
        if (!expectArguments(statement, 1)) return false;
        IkChainDocument chain;
        chain.spec.name = statement.arguments.front().text;
        chain.line = statement.line;
        for (const IkChainDocument& other : document.ikChains)
            if (other.spec.name == chain.spec.name)
                return fail(statement.line, "IK chain '" + chain.spec.name + "' is given twice (first at line " +
                                                std::to_string(other.line) + ")");
        SeenWords seen;
        for (const SyntaxStatement& c : statement.children)
        {
            const std::string& k = c.keyword;
            bool ok = true;
            if (k == "root") ok = once(seen, c) && expectNoBlock(c) && name(c, chain.spec.rootJoint);
            else if (k == "effector") ok = once(seen, c) && expectNoBlock(c) && name(c, chain.spec.effectorJoint);
            else if (k == "effector_offset") ok = once(seen, c) && vector3(c, chain.spec.effectorOffset);
            else if (k == "solver")
            {
                std::string solver;
                ok = once(seen, c) && expectNoBlock(c) && name(c, solver);
                if (ok && !parseIkSolver(solver, chain.spec.solver))
                    return fail(c.line, "unknown IK solver '" + solver + "' (twobone, ccd or dls)");
            }
            else if (k == "iterations")
            {
                double iterations = 0.0;
                ok = once(seen, c) && numbers(c, 1, &iterations);
                if (ok && !(iterations >= 1.0 && iterations <= 1e6 && iterations == std::floor(iterations)))
                    return fail(c.line, "'iterations' must be a whole number from 1 to 1000000");
                chain.spec.maxIterations = static_cast<unsigned>(iterations);
            }
            else if (k == "tolerance")
            {
                ok = once(seen, c) && numbers(c, 1, &chain.spec.tolerance);
                if (ok && !(chain.spec.tolerance > 0.0 && chain.spec.tolerance < 1.0))
                    return fail(c.line, "'tolerance' must be between 0 and 1 (a fraction of the chain's length)");
            }
            else if (k == "joint_weight" || k == "dof_weight")
            {
                IkWeightSpec weight;
                ok = expectNoBlock(c) && expectArguments(c, 2) && number(c.arguments[1], weight.weight);
                if (!ok) return false; // before reading the name: the statement may have no arguments at all
                if (weight.weight < 0.0) return fail(c.line, "'" + k + "' must not be negative");
                weight.name = c.arguments.front().text;
                (k == "joint_weight" ? chain.spec.jointWeights : chain.spec.dofWeights).push_back(weight);
            }
            else return unknownKeyword(c, "in an ikchain");
            if (!ok) return false;
        }
        if (chain.spec.rootJoint.empty())
            return fail(statement.line, "IK chain '" + chain.spec.name + "' has no 'root'");
        if (chain.spec.effectorJoint.empty())
            return fail(statement.line, "IK chain '" + chain.spec.name + "' has no 'effector'");
        document.ikChains.push_back(chain);
        return true;
    }

    /** The joint statements among statements and nested in them (readJoint() reads nested joints). */
    static std::size_t countJoints(const std::vector<SyntaxStatement>& statements)
    {
        std::size_t count = 0;
        for (const SyntaxStatement& s : statements)
            if (s.keyword == "joint") count += 1 + countJoints(s.children);
        return count;
    }

    /** A joint and, nested in it, its children; parentName is empty for a joint at the actor's level. */
    bool readJoint(const SyntaxStatement& statement, const std::string& parentName, ActorDocument& document)
    {
        if (!expectArguments(statement, 1)) return false;
        const std::size_t index = document.joints.size();
        document.joints.emplace_back();
        {
            JointDocument& joint = document.joints.back();
            joint.spec.name = statement.arguments.front().text;
            joint.spec.parent = parentName;
            joint.line = statement.line;
        }
        SeenWords seen;
        for (const SyntaxStatement& s : statement.children)
        {
            const std::string& k = s.keyword;
            if (k == "joint")
            {
                // Read the child first: it may grow the vector, so take no reference across this call.
                const std::string name = document.joints[index].spec.name;
                if (!readJoint(s, name, document)) return false;
                continue;
            }
            JointDocument& joint = document.joints[index];
            bool ok = true;
            if (k == "parent")
            {
                if (!parentName.empty())
                    return fail(s.line, "a nested joint's parent is the joint it is nested in; 'parent' is for "
                                        "joints at the actor's level");
                ok = once(seen, s) && expectNoBlock(s) && name(s, joint.spec.parent);
            }
            else if (k == "offset") ok = once(seen, s) && vector3(s, joint.spec.translation);
            else if (k == "rotation") ok = once(seen, s) && rotation(s, joint.spec.rotation);
            else if (k == "euler") ok = once(seen, s) && readEulerOrder(s, joint.spec.eulerOrder);
            else if (k == "translation_mode") ok = once(seen, s) && readTranslationMode(s, joint.spec.translationMode);
            else if (k == "dof") ok = readDof(s, joint);
            else if (k == "hidden") ok = flag(seen, s, joint.hidden);
            else if (k == "shape") ok = readShape(s, joint);
            else if (k == "model") ok = readModel(s, joint);
            else return unknownKeyword(s, "in a joint");
            if (!ok) return false;
        }
        return true;
    }

    bool readEulerOrder(const SyntaxStatement& s, EulerOrder& order)
    {
        if (!expectNoBlock(s) || !expectArguments(s, 1)) return false;
        if (parseEulerOrder(s.arguments.front().text, order)) return true;
        return fail(s.line, "'" + s.arguments.front().text + "' is not an Euler order (XYZ, XZY, YXZ, YZX, ZXY, ZYX)");
    }

    bool readBounds(const SyntaxStatement& s, bool& coverRotations)
    {
        if (!expectNoBlock(s) || !expectArguments(s, 1)) return false;
        const std::string& word = s.arguments.front().text;
        if (parseBounds(word, coverRotations)) return true;
        return fail(s.line, "'" + word + "' is not a bound mode (follows_pose, covers_rotations)");
    }

    /** "cull" and "update_policy": how the views treat the actor (ActorNode::setCullMode(), setUpdatePolicy()). */
    static bool isViewingStatement(const std::string& keyword)
    {
        return keyword == "cull" || keyword == "update_policy";
    }

    bool readViewingStatement(SeenWords& seen, const SyntaxStatement& s, ActorDocument& document)
    {
        if (!once(seen, s)) return false;
        if (s.keyword == "cull") return readCullMode(s, document.cullNodeByNode);
        return readUpdatePolicy(s, document.updatePolicy);
    }

    bool readCullMode(const SyntaxStatement& s, bool& nodeByNode)
    {
        if (!expectNoBlock(s) || !expectArguments(s, 1)) return false;
        const std::string& word = s.arguments.front().text;
        if (parseCullMode(word, nodeByNode)) return true;
        return fail(s.line, "'" + word + "' is not a cull mode (as_one, node_by_node)");
    }

    /** "update_policy { [only_when_seen] [max_distance d] [half_rate_below_pixels p] [quarter_rate_below_pixels p] }"
      * (model units, pixels). */
    bool readUpdatePolicy(const SyntaxStatement& s, UpdatePolicyDocument& policy)
    {
        if (!s.hasBlock) return fail(s.line, "'update_policy' needs a block in braces");
        if (!expectArguments(s, 0)) return false;
        SeenWords seen;
        for (const SyntaxStatement& c : s.children)
        {
            const std::string& k = c.keyword;
            bool ok = true;
            if (k == "only_when_seen") ok = flag(seen, c, policy.onlyWhenSeen);
            else if (k == "max_distance") ok = once(seen, c) && notNegative(c, policy.maxDistance);
            else if (k == "half_rate_below_pixels") ok = once(seen, c) && pixels(c, policy.halfRateBelowPixels);
            else if (k == "quarter_rate_below_pixels") ok = once(seen, c) && pixels(c, policy.quarterRateBelowPixels);
            else return unknownKeyword(c, "in 'update_policy'");
            if (!ok) return false;
        }
        return true;
    }

    bool notNegative(const SyntaxStatement& statement, double& value)
    {
        if (!numbers(statement, 1, &value)) return false;
        if (value >= 0.0) return true;
        return fail(statement.line, "'" + statement.keyword + "' must not be negative");
    }

    /** A size on screen, which ActorNode holds as a float: one that a float cannot hold (beyond its range, or so
      * small it would become 0 and so mean "off") is refused rather than changed. */
    bool pixels(const SyntaxStatement& statement, float& value)
    {
        double read = 0.0;
        if (!notNegative(statement, read)) return false;
        const float held = static_cast<float>(read);
        if (read <= std::numeric_limits<float>::max() && (held > 0.0f || read == 0.0))
        {
            value = held;
            return true;
        }
        return fail(statement.line, "'" + statement.keyword + "' " + statement.arguments.front().text +
                                        " is not a size a float holds");
    }

    bool readTranslationMode(const SyntaxStatement& s, TranslationMode& mode)
    {
        if (!expectNoBlock(s) || !expectArguments(s, 1)) return false;
        const std::string& word = s.arguments.front().text;
        if (parseTranslationMode(word, mode)) return true;
        return fail(s.line, "'" + word + "' is not a translation mode (after_rotation, before_rotation)");
    }

    /** "dof rx [min a] [max b] [default c] [weight w] [value v]": degrees for rotations, model units otherwise. */
    bool readDof(const SyntaxStatement& s, JointDocument& joint)
    {
        if (!expectNoBlock(s)) return false;
        if (s.arguments.empty()) return fail(s.line, "'dof' needs a DOF name (rx, ry, rz, tx, ty, tz)");
        Dof dof;
        if (!parseDof(s.arguments.front().text, dof))
            return fail(s.line, "'" + s.arguments.front().text + "' is not a DOF (rx, ry, rz, tx, ty, tz)");
        DofSpec& spec = joint.spec.dofs[static_cast<unsigned>(dof)];
        if (spec.active) return fail(s.line, "DOF '" + s.arguments.front().text + "' is given twice");
        spec.active = true;
        SeenWords seen;
        for (std::size_t i = 1; i < s.arguments.size(); i += 2)
        {
            const SyntaxArgument& key = s.arguments[i];
            if (i + 1 >= s.arguments.size()) return fail(key.line, "'" + key.text + "' needs a value");
            double value = 0.0;
            if (!dofValue(s.arguments[i + 1], isRotation(dof) && key.text != "weight", value)) return false;
            if (!seen.insert(key.text)) return fail(key.line, "'" + key.text + "' is given twice");
            if (key.text == "min") spec.min = value;
            else if (key.text == "max") spec.max = value;
            else if (key.text == "default") spec.defaultValue = value;
            else if (key.text == "weight") spec.weight = value;
            else if (key.text == "value") joint.values[static_cast<unsigned>(dof)] = value;
            else return fail(key.line, "unknown DOF attribute '" + key.text + "' (min, max, default, weight, value)");
        }
        // The builder checks the default against the limits; the current value is the file's to check.
        const std::optional<double>& value = joint.values[static_cast<unsigned>(dof)];
        if (value && (*value < spec.min || *value > spec.max))
            return fail(s.line, "the value of DOF '" + s.arguments.front().text + "' lies outside its limits");
        if (value && std::abs(*value) > kMaxDofMagnitude)
            return fail(s.line, "the value of DOF '" + s.arguments.front().text +
                                    "' lies beyond what a pose holds (+-" + formatNumber(kMaxDofMagnitude) +
                                    (isRotation(dof) ? " radians)" : ")"));
        return true;
    }

    bool readShape(const SyntaxStatement& s, JointDocument& joint)
    {
        GeometryDescription shape;
        shape.line = s.line;
        if (!expectArguments(s, 1)) return false;
        if (!parseShapeKind(s.arguments.front().text, shape.kind))
            return fail(s.line, "'" + s.arguments.front().text +
                                    "' is not a shape (box, sphere, capsule, cylinder, cone)");
        const bool isBox = shape.kind == GeometryKind::Box;
        const bool hasHeight = !isBox && shape.kind != GeometryKind::Sphere;
        SeenWords seen;
        for (const SyntaxStatement& c : s.children)
        {
            const std::string& k = c.keyword;
            const bool applies = (k == "size" && isBox) || (k == "radius" && !isBox) || (k == "height" && hasHeight) ||
                                 k == "position" || k == "rotation" || k == "color";
            if (!applies)
            {
                if (k == "size" || k == "radius" || k == "height")
                    return fail(c.line, "'" + k + "' does not apply to a " + geometryKindName(shape.kind));
                return unknownKeyword(c, "in a shape");
            }
            if (!once(seen, c)) return false;
            bool ok = true;
            if (k == "size") ok = vector3(c, shape.size);
            else if (k == "radius") ok = positive(c, shape.radius);
            else if (k == "height") ok = positive(c, shape.height);
            else if (k == "position") ok = vector3(c, shape.position);
            else if (k == "rotation") ok = rotation(c, shape.rotation);
            else ok = readColor(c, shape.color);
            if (!ok) return false;
        }
        if (isBox && !(seen.count("size") && shape.size.x > 0.0 && shape.size.y > 0.0 && shape.size.z > 0.0))
            return fail(s.line, "a box needs a 'size' of three lengths greater than zero");
        if (!isBox && !seen.count("radius"))
            return fail(s.line, std::string("a ") + geometryKindName(shape.kind) + " needs a 'radius'");
        if (hasHeight && !seen.count("height"))
            return fail(s.line, std::string("a ") + geometryKindName(shape.kind) + " needs a 'height'");
        joint.geometry.push_back(shape);
        return true;
    }

    bool readColor(const SyntaxStatement& s, glm::dvec4& color)
    {
        if (!expectNoBlock(s)) return false;
        if (s.arguments.size() != 3 && s.arguments.size() != 4)
            return fail(s.line, "'color' takes 3 or 4 values (red, green, blue, optional alpha, each 0 to 1)");
        double v[4] = {1.0, 1.0, 1.0, 1.0};
        for (std::size_t i = 0; i < s.arguments.size(); ++i)
        {
            if (!number(s.arguments[i], v[i])) return false;
            if (v[i] < 0.0 || v[i] > 1.0) return fail(s.line, "colour components lie between 0 and 1");
        }
        color = glm::dvec4(v[0], v[1], v[2], v[3]);
        return true;
    }

    bool readModel(const SyntaxStatement& s, JointDocument& joint)
    {
        GeometryDescription model;
        model.kind = GeometryKind::Model;
        model.line = s.line;
        if (!expectArguments(s, 1)) return false;
        model.file = s.arguments.front().text;
        if (model.file.empty()) return fail(s.line, "'model' needs a file name");
        SeenWords seen;
        for (const SyntaxStatement& c : s.children)
        {
            const std::string& k = c.keyword;
            bool ok = true;
            if (k == "position") ok = once(seen, c) && vector3(c, model.position);
            else if (k == "rotation") ok = once(seen, c) && rotation(c, model.rotation);
            else if (k == "scale") ok = once(seen, c) && positive(c, model.scale);
            else return unknownKeyword(c, "in a model");
            if (!ok) return false;
        }
        joint.geometry.push_back(model);
        return true;
    }

    // --- clips ---

    /** Whether a channel's values are angles (it drives a rotation DOF) or lengths. */
    bool channelIsAngular(const SyntaxArgument& target, const ActorDefinition& definition, bool& angular)
    {
        const int dof = definition.findDof(target.text);
        if (dof < 0) return fail(target.line, "channel '" + target.text + "' names no DOF of the actor");
        angular = isRotation(definition.getDofType(static_cast<unsigned>(dof)));
        return true;
    }

    bool readInterpolation(const SyntaxStatement& s, Interpolation& interpolation)
    {
        if (!expectNoBlock(s) || !expectArguments(s, 1)) return false;
        const std::string& word = s.arguments.front().text;
        if (parseInterpolation(word, interpolation)) return true;
        return fail(s.line, "'" + word + "' is not an interpolation (step, linear, cubic)");
    }

    /** "channel target { [interpolation i] key time value ... }": a keyed channel. */
    bool readChannel(const SyntaxStatement& s, const ActorDefinition& definition, ClipBuilder& builder)
    {
        if (!expectArguments(s, 1)) return false;
        bool angular = false;
        if (!channelIsAngular(s.arguments.front(), definition, angular)) return false;
        Interpolation interpolation = Interpolation::Linear;
        std::vector<std::pair<double, double>> keys; // seconds, API units
        SeenWords seen;
        for (const SyntaxStatement& c : s.children)
        {
            if (c.keyword == "interpolation")
            {
                if (!once(seen, c) || !readInterpolation(c, interpolation)) return false;
            }
            else if (c.keyword == "key")
            {
                double v[2];
                if (!expectNoBlock(c) || !expectArguments(c, 2) || !number(c.arguments[0], v[0]) ||
                    !dofValue(c.arguments[1], angular, v[1]))
                    return false;
                if (!keys.empty() && !(v[0] > keys.back().first))
                    return fail(c.line, "key times must increase");
                keys.emplace_back(v[0], v[1]);
            }
            else return unknownKeyword(c, "in a channel");
        }
        if (keys.empty()) return fail(s.line, "channel '" + s.arguments.front().text + "' has no key");
        const unsigned channel = builder.addChannel(s.arguments.front().text, interpolation);
        for (const auto& key : keys) builder.addKey(channel, key.first, key.second);
        return true;
    }

    /** "frame_rate r", "channels t1 t2 ...", "frame v1 v2 ...": a uniform clip, one frame per statement. */
    bool readFrames(const SyntaxStatement& clip, const ActorDefinition& definition, ClipBuilder& builder)
    {
        double frameRate = 0.0;
        std::vector<bool> angular; // per channel
        std::vector<double> values;
        SeenWords seen;
        for (const SyntaxStatement& c : clip.children)
        {
            if (c.keyword == "frame_rate")
            {
                if (!once(seen, c) || !positive(c, frameRate)) return false;
            }
            else if (c.keyword == "channels")
            {
                if (!once(seen, c) || !expectNoBlock(c)) return false;
                if (c.arguments.empty()) return fail(c.line, "'channels' needs at least one DOF name");
                for (const SyntaxArgument& target : c.arguments)
                {
                    bool isAngle = false;
                    if (!channelIsAngular(target, definition, isAngle)) return false;
                    angular.push_back(isAngle);
                    builder.addChannel(target.text);
                }
            }
            else if (c.keyword == "frame")
            {
                if (angular.empty()) return fail(c.line, "'frame' must follow 'channels'");
                if (!expectNoBlock(c) || !expectArguments(c, angular.size())) return false;
                for (std::size_t i = 0; i < angular.size(); ++i)
                {
                    double value = 0.0;
                    if (!dofValue(c.arguments[i], angular[i], value)) return false;
                    values.push_back(value);
                }
            }
            else if (c.keyword == "play") continue; // read by readClip
            else return unknownKeyword(c, "in a clip of frames");
        }
        if (!seen.count("frame_rate")) return fail(clip.line, "a clip of frames needs a 'frame_rate'");
        if (values.empty()) return fail(clip.line, "a clip of frames needs at least one 'frame'");
        builder.setFrames(frameRate, std::move(values));
        return true;
    }

    /** "file "walk.bvh" [{ options }]", "file "walk.amc" { skeleton "walk.asf" [options] }" or
      * "file "hero.gltf" [{ animation "walk"; up y|z }]" (a rigged model's animation, .gltf or .glb): where a clip's
      * motion is, and how to read it (MotionFileOptions). An option that does nothing for the file's format is an
      * error, so that a file never seems to say more than it does. */
    bool readClipFile(const SyntaxStatement& s, ClipDocument& clip)
    {
        if (!expectArguments(s, 1)) return false;
        clip.file = s.arguments.front().text;
        const std::string extension = lowerExtensionOf(clip.file);
        const bool amc = extension == ".amc";
        const bool rigged = extension == ".gltf" || extension == ".glb";
        if (!amc && !rigged && extension != ".bvh")
            return fail(s.line, "'" + clip.file + "': a clip's file must be motion capture, BVH (.bvh) or AMC (.amc), "
                                "or a rigged model's animation (.gltf, .glb)");
        MotionFileOptions& options = clip.fileOptions;
        SeenWords seen;
        for (const SyntaxStatement& o : s.children)
        {
            const std::string& k = o.keyword;
            const bool bvhOnly = k == "drop_first_frame" || k == "absolute_root_position";
            const bool amcOnly = k == "skeleton" || k == "frame_rate";
            const bool riggedOnly = k == "animation";
            if (rigged && !riggedOnly && k != "up")
                return fail(o.line, "'" + k + "' is not for a rigged model's animation, and '" + clip.file + "' is one");
            if (riggedOnly && !rigged)
                return fail(o.line, "'" + k + "' is for rigged model files (.gltf, .glb), and '" + clip.file + "' is " +
                                        (amc ? "AMC" : "BVH"));
            if ((bvhOnly && amc) || (amcOnly && !amc && !rigged))
                return fail(o.line, "'" + k + "' is for " + (amc ? "BVH" : "AMC") + " files, and '" + clip.file +
                                        "' is " + (amc ? "AMC" : "BVH"));
            bool ok = true;
            if (k == "scale") ok = once(seen, o) && positive(o, options.scale);
            else if (k == "up") ok = once(seen, o) && readUpAxis(o, options.fileUpAxis);
            else if (k == "drop_first_frame") ok = flag(seen, o, options.dropFirstFrame);
            else if (k == "absolute_root_position") ok = flag(seen, o, options.absoluteRootPosition);
            else if (k == "frame_rate") ok = once(seen, o) && positive(o, options.amcFrameRate);
            else if (k == "animation")
            {
                ok = once(seen, o) && expectNoBlock(o) && expectArguments(o, 1);
                if (ok) options.animation = o.arguments.front().text;
            }
            else if (k == "skeleton")
            {
                ok = once(seen, o) && expectNoBlock(o) && expectArguments(o, 1);
                if (ok) options.skeletonFile = o.arguments.front().text;
                if (ok && lowerExtensionOf(options.skeletonFile) != ".asf")
                    return fail(o.line, "'" + options.skeletonFile + "': an AMC motion's skeleton must be ASF (.asf)");
            }
            else return unknownKeyword(o, "in a clip's file block");
            if (!ok) return false;
        }
        if (amc && options.skeletonFile.empty())
            return fail(s.line, "'" + clip.file + "': an AMC motion needs its ASF skeleton: 'skeleton \"x.asf\"' in a "
                                "block after the file name");
        return true;
    }

    /** "player name { clip c | trajectory t [play mode] [paused] [time t] [speed s] [weight w] [disabled]
      * [fade w] [root_motion mode [joint]] [sway_window s] [dof name weight ...] }": the last four for a clip's
      * player only. */
    bool readPlayer(const SyntaxStatement& s, const ActorDefinition& definition, const ActorDocument& document,
                    PlayerDocument& player)
    {
        if (!expectArguments(s, 1)) return false;
        player.name = s.arguments.front().text;
        player.line = s.line;
        bool paused = false;
        SeenWords seen;
        const SyntaxStatement* clipOnly = nullptr; // the first statement only a clip's player takes
        for (const SyntaxStatement& c : s.children)
        {
            const std::string& k = c.keyword;
            bool ok = true;
            if (k == "fade" || k == "root_motion" || k == "sway_window" || k == "dof")
                clipOnly = clipOnly ? clipOnly : &c;
            if (k == "clip") ok = once(seen, c) && expectNoBlock(c) && name(c, player.clip);
            else if (k == "trajectory") ok = once(seen, c) && expectNoBlock(c) && name(c, player.trajectory);
            else if (k == "play")
            {
                ok = once(seen, c) && readPlayMode(c, player.playMode);
                player.playing = ok;
            }
            else if (k == "paused") ok = flag(seen, c, paused);
            else if (k == "time")
            {
                double time = 0.0;
                ok = once(seen, c) && numbers(c, 1, &time);
                player.time = time;
            }
            else if (k == "speed") ok = once(seen, c) && numbers(c, 1, &player.speed);
            else if (k == "weight") ok = once(seen, c) && unitWeight(c, player.weight);
            else if (k == "fade") ok = once(seen, c) && unitWeight(c, player.fade);
            else if (k == "disabled")
            {
                bool disabled = false;
                ok = flag(seen, c, disabled);
                player.enabled = !disabled;
            }
            else if (k == "root_motion") ok = once(seen, c) && readRootMotion(c, definition, player);
            else if (k == "sway_window")
            {
                ok = once(seen, c) && numbers(c, 1, &player.swayWindow);
                if (ok && player.swayWindow < 0.0) return fail(c.line, "'sway_window' must not be negative");
            }
            else if (k == "dof") ok = readDofWeight(c, definition, player);
            else return unknownKeyword(c, "in a player");
            if (!ok) return false;
        }
        if (!seen.count("play")) player.playMode = player.defaultPlayMode();
        player.playing = player.playing && !paused;
        return checkPlays(s, document, player, clipOnly);
    }

    /** A player plays one clip or one trajectory of the actor, and takes a clip's options only for a clip. */
    bool checkPlays(const SyntaxStatement& s, const ActorDocument& document, const PlayerDocument& player,
                    const SyntaxStatement* clipOnly)
    {
        const std::string who = "player '" + player.name + "'";
        if (player.clip.empty() == player.trajectory.empty())
            return fail(s.line, who + " needs either the 'clip' or the 'trajectory' it plays");
        if (player.playsTrajectory())
        {
            if (clipOnly) return fail(clipOnly->line, "'" + clipOnly->keyword + "' is for a clip's player, and " +
                                                          who + " plays a trajectory");
            const bool known = std::any_of(document.trajectories.begin(), document.trajectories.end(),
                                           [&](const TrajectoryDocument& t) { return t.name() == player.trajectory; });
            if (!known)
                return fail(s.line,
                            who + " plays trajectory '" + player.trajectory + "', which the actor does not have");
            return true;
        }
        const bool known = std::any_of(document.clips.begin(), document.clips.end(),
                                       [&](const ClipDocument& clip) { return clip.name() == player.clip; });
        if (!known) return fail(s.line, who + " plays clip '" + player.clip + "', which the actor does not have");
        return true;
    }

    /** A weight in [0, 1] ("weight", "fade", a DOF's). */
    bool unitWeight(const SyntaxStatement& s, double& value)
    {
        if (!numbers(s, 1, &value)) return false;
        if (value >= 0.0 && value <= 1.0) return true;
        return fail(s.line, "'" + s.keyword + "' must be from 0 to 1");
    }

    /** "root_motion in_skeleton|to_transforms|in_place [joint]" */
    bool readRootMotion(const SyntaxStatement& s, const ActorDefinition& definition, PlayerDocument& player)
    {
        if (!expectNoBlock(s)) return false;
        if (s.arguments.empty() || s.arguments.size() > 2) return expectArguments(s, 1);
        if (!parseRootMotion(s.arguments.front().text, player.rootMotion))
            return fail(s.line, "'" + s.arguments.front().text +
                                    "' is not a root motion (in_skeleton, to_transforms, in_place)");
        if (s.arguments.size() == 2)
        {
            player.rootJoint = s.arguments[1].text;
            if (definition.findJoint(player.rootJoint) < 0)
                return fail(s.line, "'" + player.rootJoint + "' is not a joint of the actor");
        }
        return true;
    }

    /** "dof name weight": one DOF of the player's selection. */
    bool readDofWeight(const SyntaxStatement& s, const ActorDefinition& definition, PlayerDocument& player)
    {
        if (!expectNoBlock(s) || !expectArguments(s, 2)) return false;
        const std::string& dofName = s.arguments.front().text;
        if (definition.findDof(dofName) < 0) return fail(s.line, "'" + dofName + "' names no DOF of the actor");
        for (const auto& given : player.dofWeights)
            if (given.first == dofName) return fail(s.line, "DOF '" + dofName + "' is given twice");
        double weight = 0.0;
        if (!number(s.arguments[1], weight)) return false;
        if (!(weight >= 0.0 && weight <= 1.0)) return fail(s.line, "a DOF's weight must be from 0 to 1");
        player.dofWeights.emplace_back(dofName, weight);
        return true;
    }

    /** "play once|loop|pingpong" of a clip or a trajectory. */
    bool readPlayMode(const SyntaxStatement& s, PlayMode& mode)
    {
        if (!expectNoBlock(s) || !expectArguments(s, 1)) return false;
        if (parsePlayMode(s.arguments.front().text, mode)) return true;
        return fail(s.line, "'" + s.arguments.front().text + "' is not a play mode (once, loop, pingpong)");
    }

    bool readUpAxis(const SyntaxStatement& s, UpAxis& axis)
    {
        if (!expectNoBlock(s) || !expectArguments(s, 1)) return false;
        const std::string& word = s.arguments.front().text;
        if (parseUpAxis(word, axis)) return true;
        return fail(s.line, "'" + word + "' is not an up axis (y, z)");
    }

    /** "clip name { channel ... }" (keys), "clip name { frame_rate ...; channels ...; frame ... }" (frames), or
      * "clip name { file "walk.bvh" }" (read later, see ClipDocument::file). */
    bool readClip(const SyntaxStatement& s, const ActorDefinition& definition, ClipDocument& clip)
    {
        if (!expectArguments(s, 1)) return false;
        ClipBuilder builder(s.arguments.front().text);
        bool keyed = false;
        bool uniform = false;
        SeenWords seen;
        for (const SyntaxStatement& c : s.children)
        {
            if (c.keyword == "play")
            {
                if (!once(seen, c) || !readPlayMode(c, clip.playMode)) return false;
                clip.play = true;
                continue;
            }
            if (c.keyword == "file")
            {
                if (!once(seen, c) || !readClipFile(c, clip)) return false;
                continue;
            }
            if (c.keyword == "retarget")
            {
                if (!once(seen, c) || !readClipRetarget(c, _fileName, clip.retarget, _error)) return false;
                continue;
            }
            const bool isChannel = c.keyword == "channel";
            if (!isChannel && c.keyword != "frame_rate" && c.keyword != "channels" && c.keyword != "frame")
                return unknownKeyword(c, "in a clip");
            keyed = keyed || isChannel;
            uniform = uniform || !isChannel;
            if (keyed && uniform) return fail(c.line, "a clip has either 'channel' blocks or frames, not both");
        }
        if (clip.retarget.enabled && clip.file.empty())
            return fail(clip.retarget.line, "'retarget' is for a clip whose motion is in a file");
        if (!clip.file.empty())
        {
            if (keyed || uniform)
                return fail(s.line, "clip '" + s.arguments.front().text +
                                        "' reads its motion from a file, so it has no channels or frames of its own");
            clip.fileOptions.name = s.arguments.front().text;
            return true;
        }
        if (keyed)
        {
            for (const SyntaxStatement& c : s.children)
                if (c.keyword != "play" && !readChannel(c, definition, builder)) return false;
        }
        else if (uniform)
        {
            if (!readFrames(s, definition, builder)) return false;
        }
        else
        {
            return fail(s.line, "clip '" + s.arguments.front().text + "' has no channel");
        }
        const ClipBuildResult built = builder.build();
        if (!built) return fail(s.line, built.error);
        clip.clip = built.clip;
        return true;
    }

    const std::string& _fileName;
    std::string _error;
    std::vector<const SyntaxStatement*> _clipStatements; // point into the caller's statements
    std::vector<const SyntaxStatement*> _playerStatements; // likewise
};

/** Joints in the definition's order (parents first, depth first, each parent's children in file order): the order
  * the writer nests them in, so that what it writes reads back in the same order whatever order the file gave
  * (joints at the actor's level with 'parent' statements come in any). */
void putInDefinitionOrder(const ActorDefinition& definition, std::vector<JointDocument>& joints)
{
    // A file that nests its joints (or lists parents first) gives them in this order already: then a look at the
    // names is all, with no second copy of every joint.
    bool inOrder = true;
    for (unsigned j = 0; j < joints.size() && inOrder; ++j) inOrder = joints[j].spec.name == definition.getJointName(j);
    if (inOrder) return;
    // The definition was built from these joints, so it knows each name once: its index is the joint's place.
    std::vector<JointDocument> ordered(joints.size());
    for (JointDocument& joint : joints)
        ordered[static_cast<unsigned>(definition.findJoint(joint.spec.name))] = std::move(joint);
    joints.swap(ordered);
}

} // namespace

ActorReadResult readActor(std::istream& in, const std::string& fileName)
{
    ActorReadResult result;
    std::vector<SyntaxStatement> statements;
    if (!parseSyntax(in, fileName, statements, result.error)) return result;
    DocumentReader reader(fileName);
    ActorDocument document;
    if (!reader.readFile(statements, document))
    {
        result.error = reader.error();
        return result;
    }
    BuildResult built = buildDefinition(document, fileName);
    if (!built)
    {
        result.error = built.error;
        return result;
    }
    putInDefinitionOrder(*built.definition, document.joints);
    if (!checkActorJointMaps(document.sections, *built.definition, fileName, result.error)) return result;
    if (!reader.readClips(*built.definition, document))
    {
        result.error = reader.error();
        return result;
    }
    if (!reader.readPlayers(*built.definition, document))
    {
        result.error = reader.error();
        return result;
    }
    if (!buildIkChains(document, *built.definition, fileName, result.ikChains, result.error)) return result;
    result.document = std::move(document);
    result.definition = built.definition;
    return result;
}

ActorReadResult readActorMotion(std::istream& in, const std::string& fileName, const ActorDefinitionPtr& definition,
                                const std::vector<ClipPtr>& knownClips)
{
    ActorReadResult result;
    if (!definition)
    {
        result.error = fileName + ": an actor's motion needs the actor's definition";
        return result;
    }
    std::vector<SyntaxStatement> statements;
    if (!parseSyntax(in, fileName, statements, result.error)) return result;
    DocumentReader reader(fileName);
    ActorDocument document;
    document.name = definition->getName();
    if (!reader.readMotionFile(statements, document) || !reader.readClips(*definition, document))
    {
        result.error = reader.error();
        return result;
    }
    for (const ClipPtr& known : knownClips)
    {
        for (const ClipDocument& clip : document.clips)
        {
            if (clip.name() != known->getName()) continue;
            result.error = fileName + ":" + std::to_string(clip.line) + ": clip '" + clip.name() +
                           "' is in the actor's clip library already";
            return result;
        }
    }
    // The known clips come first, as the library's clips do in a whole file: players may play them.
    std::vector<ClipDocument> clips(knownClips.size());
    for (std::size_t i = 0; i < knownClips.size(); ++i) clips[i].clip = knownClips[i];
    document.clips.insert(document.clips.begin(), clips.begin(), clips.end());
    if (!reader.readPlayers(*definition, document))
    {
        result.error = reader.error();
        return result;
    }
    if (!buildIkChains(document, *definition, fileName, result.ikChains, result.error)) return result;
    result.document = std::move(document);
    result.definition = definition;
    return result;
}

} // namespace osgActor
