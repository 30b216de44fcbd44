#include <osgActor/io/JointMapSection>
#include <osgActor/core/retarget/BuiltInJointMaps>

#include <fstream>
#include <set>

namespace osgActor {

namespace {

std::string at(const std::string& fileName, int line) { return fileName + ":" + std::to_string(line); }

} // namespace

bool readJointMapStatements(const std::vector<SyntaxStatement>& statements, const std::string& fileName,
                            JointMap& map, std::string& error)
{
    std::set<std::string> mapped;
    for (std::size_t i = 0; i < statements.size(); ++i)
    {
        const SyntaxStatement& s = statements[i];
        const std::string where = at(fileName, s.line) + ": ";
        if (s.hasBlock)
        {
            error = where + "'" + s.keyword + "' takes no block";
            return false;
        }
        if (s.keyword == "base")
        {
            JointMapStyle style;
            if (i != 0)
            {
                error = where + "'base' must come first in a joint map";
                return false;
            }
            if (s.arguments.size() != 1 || !parseJointMapStyle(s.arguments[0].text, style))
            {
                error = where + "'base' takes one of hanim, cmu_asf, cmu_bvh, motionbuilder_bvh, mixamo, makehuman";
                return false;
            }
            const std::string name = map.getName();
            map = builtInJointMap(style);
            map.setName(name);
        }
        else if (s.keyword == "map")
        {
            if (s.arguments.size() != 2)
            {
                error = where + "'map' takes a joint and its H-Anim joint, not " + std::to_string(s.arguments.size()) +
                        " value" + (s.arguments.size() == 1 ? "" : "s");
                return false;
            }
            if (!mapped.insert(s.arguments[0].text).second)
            {
                error = where + "joint '" + s.arguments[0].text + "' is mapped twice";
                return false;
            }
            map.add(s.arguments[0].text, s.arguments[1].text, at(fileName, s.line));
        }
        else
        {
            error = where + "unknown keyword '" + s.keyword + "' in a joint map (base, map)";
            return false;
        }
    }
    return true;
}

bool readJointMapFile(const std::string& path, JointMap& map, std::string& error)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        error = path + ": cannot open the joint map file";
        return false;
    }
    std::vector<SyntaxStatement> statements;
    if (!parseSyntax(in, path, statements, error)) return false;
    map = JointMap(path);
    return readJointMapStatements(statements, path, map, error);
}

bool readActorJointMaps(const std::vector<SyntaxStatement>& sections, const std::string& fileName,
                        ActorJointMaps& maps, std::string& error)
{
    for (const SyntaxStatement& section : sections)
    {
        if (section.keyword != "jointmap") continue;
        const std::string where = at(fileName, section.line) + ": ";
        if (section.arguments.size() > 1)
        {
            error = where + "'jointmap' takes at most a name";
            return false;
        }
        const bool named = !section.arguments.empty();
        const std::string name = named ? section.arguments[0].text : std::string();
        if ((named && maps.named.count(name)) || (!named && maps.hasOwn))
        {
            error = where +
                    (named ? "joint map '" + name + "' is given twice" : "the actor's joint map is given twice");
            return false;
        }
        JointMap map(name);
        if (!readJointMapStatements(section.children, fileName, map, error)) return false;
        if (named)
            maps.named[name] = map;
        else
        {
            maps.own = map;
            maps.hasOwn = true;
        }
    }
    return true;
}

bool checkActorJointMaps(const std::vector<SyntaxStatement>& sections, const ActorDefinition& actor,
                         const std::string& fileName, std::string& error)
{
    ActorJointMaps maps;
    if (!readActorJointMaps(sections, fileName, maps, error)) return false;
    if (!maps.hasOwn) return true;
    const JointMapResolveResult resolved = resolveJointMap(maps.own, actor);
    if (!resolved) error = resolved.error;
    return static_cast<bool>(resolved);
}

} // namespace osgActor
