#include <osgActor/core/retarget/JointMap>
#include <osgActor/core/retarget/HAnimHumanoid>

#include <algorithm>
#include <cctype>
#include <unordered_map>
#include <unordered_set>

namespace osgActor {

void JointMap::add(const std::string& joint, const std::string& hanim, const std::string& origin)
{
    const std::string key = matchKey(joint);
    for (JointMapEntry& entry : _entries)
        if (matchKey(entry.joint) == key)
        {
            entry = JointMapEntry{joint, hanim, origin};
            return;
        }
    _entries.push_back(JointMapEntry{joint, hanim, origin});
}

const JointMapEntry* JointMap::find(const std::string& joint) const
{
    const std::string key = matchKey(joint);
    for (const JointMapEntry& entry : _entries)
        if (matchKey(entry.joint) == key) return &entry;
    return nullptr;
}

std::string JointMap::matchKey(const std::string& jointName) const
{
    if (!_loose) return jointName;
    const std::size_t colon = jointName.rfind(':');
    std::string key = colon == std::string::npos ? jointName : jointName.substr(colon + 1);
    std::transform(key.begin(), key.end(), key.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return key;
}

namespace {

/** "map 'cmu' (map.txt:3)" or "map 'cmu'", to start a message about an entry. */
std::string whereIs(const JointMap& map, const JointMapEntry& entry)
{
    std::string text = "joint map";
    if (!map.getName().empty()) text += " '" + map.getName() + "'";
    if (!entry.origin.empty()) text = entry.origin + ": " + text;
    return text;
}

bool isAncestor(const ActorDefinition& definition, unsigned ancestor, unsigned joint)
{
    for (int j = definition.getParent(joint); j >= 0; j = definition.getParent(static_cast<unsigned>(j)))
        if (static_cast<unsigned>(j) == ancestor) return true;
    return false;
}

/** Follows an entry's H-Anim name through aliases to an H-Anim joint index; -1 and a message when it leads nowhere or
  * round in a cycle. */
int followToHAnim(const JointMap& map, const std::unordered_map<std::string, unsigned>& entryOfKey,
                  const JointMapEntry& start, std::string& error)
{
    std::vector<std::string> path{start.joint};
    std::unordered_set<std::string> seen{map.matchKey(start.joint)};
    std::string name = start.hanim;
    for (;;)
    {
        const int hanim = findHAnimJoint(name);
        if (hanim >= 0) return hanim;
        const auto next = entryOfKey.find(map.matchKey(name));
        if (next == entryOfKey.end())
        {
            error = whereIs(map, start) + " maps '" + start.joint + "' to '" + name +
                    "', which is neither an H-Anim joint name nor mapped itself";
            return -1;
        }
        path.push_back(name);
        if (!seen.insert(next->first).second)
        {
            error = whereIs(map, start) + " has a cycle: ";
            for (std::size_t i = 0; i < path.size(); ++i) error += (i ? " -> " : "") + path[i];
            return -1;
        }
        name = map.getEntries()[next->second].hanim;
    }
}

} // namespace

JointMapResolveResult resolveJointMap(const JointMap& map, const ActorDefinition& definition)
{
    JointMapResolveResult result;
    const std::vector<JointMapEntry>& entries = map.getEntries();
    const unsigned numJoints = definition.getNumJoints();

    std::unordered_map<std::string, unsigned> entryOfKey;
    std::unordered_set<std::string> aliasKeys; // names entries point at that are not H-Anim names
    for (unsigned e = 0; e < entries.size(); ++e)
    {
        entryOfKey[map.matchKey(entries[e].joint)] = e;
        if (findHAnimJoint(entries[e].hanim) < 0) aliasKeys.insert(map.matchKey(entries[e].hanim));
    }

    // Each entry's H-Anim joint, aliases followed.
    std::vector<int> hanimOfEntry(entries.size(), -1);
    for (unsigned e = 0; e < entries.size(); ++e)
    {
        hanimOfEntry[e] = followToHAnim(map, entryOfKey, entries[e], result.error);
        if (hanimOfEntry[e] < 0) return result;
    }

    // The joints the entries name.
    std::unordered_map<std::string, unsigned> jointOfKey;
    for (unsigned j = 0; j < numJoints; ++j) jointOfKey.emplace(map.matchKey(definition.getJointName(j)), j);
    if (!map.getLooseMatching())
        for (const JointMapEntry& entry : entries)
        {
            const std::string key = map.matchKey(entry.joint);
            if (jointOfKey.count(key) == 0 && aliasKeys.count(key) == 0)
            {
                result.error = whereIs(map, entry) + " names joint '" + entry.joint + "', which the skeleton '" +
                               definition.getName() + "' does not have";
                return result;
            }
        }

    std::vector<int>& hanimOfJoint = result.map.hanimOfJoint;
    hanimOfJoint.assign(numJoints, -1);
    std::vector<const JointMapEntry*> entryOfJoint(numJoints, nullptr);
    for (unsigned j = 0; j < numJoints; ++j)
    {
        const auto found = entryOfKey.find(map.matchKey(definition.getJointName(j)));
        if (found == entryOfKey.end()) continue;
        hanimOfJoint[j] = hanimOfEntry[found->second];
        entryOfJoint[j] = &entries[found->second];
    }

    // Parents first: a joint's nearest mapped ancestor of another H-Anim joint must map above it in H-Anim's tree,
    // and joints sharing an H-Anim joint must descend from one another.
    std::vector<int> lastJointOfHAnim(getNumHAnimJoints(), -1);
    for (unsigned j = 0; j < numJoints; ++j)
    {
        const int hanim = hanimOfJoint[j];
        if (hanim < 0) continue;
        std::string problem;
        const int sibling = lastJointOfHAnim[hanim];
        if (sibling >= 0 && !isAncestor(definition, static_cast<unsigned>(sibling), j))
            problem = "joints '" + definition.getJointName(static_cast<unsigned>(sibling)) + "' and '" +
                      definition.getJointName(j) + "' both map to " + getHAnimJoint(hanim).name +
                      " but neither lies below the other";
        else
        {
            int above = definition.getParent(j);
            while (above >= 0 && (hanimOfJoint[above] < 0 || hanimOfJoint[above] == hanim))
                above = definition.getParent(static_cast<unsigned>(above));
            if (above >= 0 && !isHAnimAncestor(hanimOfJoint[above], hanim))
                problem = "joint '" + definition.getJointName(j) + "' (" + getHAnimJoint(hanim).name +
                          ") lies below '" + definition.getJointName(static_cast<unsigned>(above)) + "' (" +
                          getHAnimJoint(hanimOfJoint[above]).name + "), which H-Anim does not put above " +
                          getHAnimJoint(hanim).name;
        }
        if (problem.empty())
        {
            lastJointOfHAnim[hanim] = static_cast<int>(j);
            continue;
        }
        if (!map.getLooseMatching())
        {
            result.error = whereIs(map, *entryOfJoint[j]) + ": " + problem;
            return result;
        }
        result.map.dropped.push_back(problem);
        hanimOfJoint[j] = -1;
    }

    for (int hanim : hanimOfJoint)
        if (hanim >= 0) ++result.map.numMapped;
    result.ok = true;
    return result;
}

} // namespace osgActor
