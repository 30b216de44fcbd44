#include <osgActor/io/ActorNumbers>
#include <osgActor/io/ActorReader>

#include <glm/ext/scalar_constants.hpp>

#include <cmath>
#include <set>

namespace osgActor {

namespace {

constexpr double kRadiansPerDegree = glm::pi<double>() / 180.0;

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
    bool once(std::set<std::string>& seen, const SyntaxStatement& statement)
    {
        if (seen.insert(statement.keyword).second) return true;
        return fail(statement.line, "'" + statement.keyword + "' is given twice");
    }

    bool number(const SyntaxArgument& argument, double& value)
    {
        if (!argument.quoted && parseNumber(argument.text, value)) return true;
        if (!argument.quoted && isNonFiniteNumber(argument.text))
            return fail(argument.line, "'" + argument.text + "' is not a finite number");
        return fail(argument.line, "'" + argument.text + "' is not a number");
    }

    /** A statement without values or block that sets a flag ("hidden", "blocked"). */
    bool flag(std::set<std::string>& seen, const SyntaxStatement& statement, bool& value)
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

    /** "rotation <degrees> <axis x> <axis y> <axis z>" */
    bool rotation(const SyntaxStatement& statement, glm::dquat& value)
    {
        double v[4];
        if (!numbers(statement, 4, v)) return false;
        AngleAxis angleAxis;
        angleAxis.degrees = v[0];
        for (unsigned i = 0; i < 3; ++i) angleAxis.axis[i] = v[i + 1];
        if (toQuaternion(angleAxis, value)) return true;
        return fail(statement.line, "the rotation axis is zero");
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
        std::set<std::string> seen;
        for (const SyntaxStatement& s : actor.children)
        {
            const std::string& k = s.keyword;
            bool ok = true;
            if (k == "joint") ok = readJoint(s, std::string(), document);
            else if (k == "pre_translation") ok = once(seen, s) && vector3(s, document.preTranslation);
            else if (k == "pre_rotation") ok = once(seen, s) && rotation(s, document.preRotation);
            else if (k == "post_translation") ok = once(seen, s) && vector3(s, document.postTranslation);
            else if (k == "post_rotation") ok = once(seen, s) && rotation(s, document.postRotation);
            else if (k == "blocked") ok = flag(seen, s, document.blocked);
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
        std::set<std::string> seen;
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

    bool readTranslationMode(const SyntaxStatement& s, TranslationMode& mode)
    {
        if (!expectNoBlock(s) || !expectArguments(s, 1)) return false;
        const std::string& word = s.arguments.front().text;
        if (word == "after_rotation") mode = TranslationMode::AfterRotation;
        else if (word == "before_rotation") mode = TranslationMode::BeforeRotation;
        else return fail(s.line, "'" + word + "' is not a translation mode (after_rotation, before_rotation)");
        return true;
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
        const double unit = isRotation(dof) ? kRadiansPerDegree : 1.0;
        std::set<std::string> seen;
        for (std::size_t i = 1; i < s.arguments.size(); i += 2)
        {
            const SyntaxArgument& key = s.arguments[i];
            if (i + 1 >= s.arguments.size()) return fail(key.line, "'" + key.text + "' needs a value");
            double value = 0.0;
            if (!number(s.arguments[i + 1], value)) return false;
            if (!seen.insert(key.text).second) return fail(key.line, "'" + key.text + "' is given twice");
            if (key.text == "min") spec.min = value * unit;
            else if (key.text == "max") spec.max = value * unit;
            else if (key.text == "default") spec.defaultValue = value * unit;
            else if (key.text == "weight") spec.weight = value;
            else if (key.text == "value") joint.values[static_cast<unsigned>(dof)] = value * unit;
            else return fail(key.line, "unknown DOF attribute '" + key.text + "' (min, max, default, weight, value)");
        }
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
        std::set<std::string> seen;
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
        std::set<std::string> seen;
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

    const std::string& _fileName;
    std::string _error;
};

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
    result.document = std::move(document);
    result.definition = built.definition;
    return result;
}

} // namespace osgActor
