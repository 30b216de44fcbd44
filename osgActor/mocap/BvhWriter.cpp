#include <osgActor/mocap/BvhWriter>
#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>
#include <osgActor/text/TextLines>

#include <vector>

namespace osgActor {

namespace {

const char* const kChannelNames[kNumDofTypes] = {"Xrotation", "Yrotation", "Zrotation",
                                                 "Xposition", "Yposition", "Zposition"};

/** The DOFs of a joint in the order its CHANNELS line lists them: positions, then rotations in Euler order. */
std::vector<Dof> channelOrder(const ActorDefinition& def, unsigned joint)
{
    std::vector<Dof> order;
    for (Dof dof : {Dof::TX, Dof::TY, Dof::TZ})
        if (def.getDofMask(joint) & dofBit(dof)) order.push_back(dof);
    unsigned axes[3];
    eulerOrderAxes(def.getEulerOrder(joint), axes);
    for (unsigned axis : axes)
        if (def.getDofMask(joint) & dofBit(static_cast<Dof>(axis))) order.push_back(static_cast<Dof>(axis));
    return order;
}

/** The reader's frame rate is 1 / Frame Time. */
double frameRateOf(double frameTime) { return 1.0 / frameTime; }

/** What a BVH reader names an End Site: "<parent>_end" (BvhImportOptions::endSitesAsJoints). A joint without DOFs
  * or children of that name is written as one, so that it reads back as the same joint; any other is a JOINT with
  * no channels. */
bool isEndSite(const ActorDefinition& def, unsigned joint, const std::vector<unsigned>& numChildren)
{
    const int parent = def.getParent(joint);
    return parent >= 0 && def.getDofMask(joint) == 0 && numChildren[joint] == 0 &&
           def.getJointName(joint) == def.getJointName(static_cast<unsigned>(parent)) + "_end";
}

/** A BVH reader takes a joint's name as the words after JOINT, joined by single spaces: a name is written as it
  * is only when that gives it back. */
bool readsBackAsName(const std::string& name)
{
    if (name.empty() || isBlank(name.front()) || isBlank(name.back())) return false;
    for (std::size_t i = 0; i < name.size(); ++i)
        if (name[i] == '\t' || (name[i] == ' ' && name[i + 1] == ' ')) return false;
    return true;
}

} // namespace

bool writeBvh(std::ostream& out, const ActorDefinition& def, const Clip* clip, std::string& error)
{
    const unsigned numJoints = def.getNumJoints();
    std::vector<unsigned> numChildren(numJoints, 0);
    for (unsigned j = 0; j < numJoints; ++j)
    {
        if (def.getParent(j) >= 0) ++numChildren[static_cast<unsigned>(def.getParent(j))];
        const glm::dquat& q = def.getOffsetRotation(j);
        if (q.x != 0.0 || q.y != 0.0 || q.z != 0.0)
        {
            error = "joint '" + def.getJointName(j) + "' has an offset rotation, which BVH cannot express";
            return false;
        }
        if (!readsBackAsName(def.getJointName(j)))
        {
            error = "joint '" + def.getJointName(j) +
                    "' has a name BVH cannot hold (empty, or with blanks at its ends or two in a row)";
            return false;
        }
        if ((def.getDofMask(j) & kTranslationDofs) && def.getTranslationMode(j) != TranslationMode::BeforeRotation)
        {
            error = "joint '" + def.getJointName(j) + "' translates after rotating, which BVH cannot express";
            return false;
        }
    }
    // Clip channel per DOF, or -1 (then the default value is written).
    std::vector<int> channelOf(def.getNumDofs(), -1);
    if (clip)
    {
        if (!clip->isUniform())
        {
            error = "clip '" + clip->getName() + "' is keyed; BVH needs one value per channel per frame";
            return false;
        }
        bool any = false;
        for (unsigned d = 0; d < def.getNumDofs(); ++d)
        {
            channelOf[d] = clip->findChannel(def.getDofName(d));
            any = any || channelOf[d] >= 0;
        }
        if (!any && def.getNumDofs() > 0)
        {
            error = "clip '" + clip->getName() + "' drives none of actor '" + def.getName() + "''s DOFs";
            return false;
        }
    }

    // Hierarchy: joints are parent-first and depth-first, so closing braces follow from the parent chain.
    out << "HIERARCHY\n";
    std::vector<unsigned> open; // joints whose braces are open
    std::vector<Dof> columns;
    std::vector<unsigned> columnDofs;
    for (unsigned j = 0; j < numJoints; ++j)
    {
        while (!open.empty() && static_cast<int>(open.back()) != def.getParent(j))
        {
            open.pop_back();
            out << std::string(2 * open.size(), ' ') << "}\n";
        }
        const std::string indent(2 * open.size(), ' ');
        const bool endSite = isEndSite(def, j, numChildren);
        if (endSite) out << indent << "End Site\n";
        else out << indent << (def.getParent(j) < 0 ? "ROOT " : "JOINT ") << def.getJointName(j) << "\n";
        out << indent << "{\n";
        const glm::dvec3& offset = def.getOffsetTranslation(j);
        out << indent << "  OFFSET " << formatNumber(offset.x) << " " << formatNumber(offset.y) << " "
            << formatNumber(offset.z) << "\n";
        if (!endSite)
        {
            const std::vector<Dof> order = channelOrder(def, j);
            out << indent << "  CHANNELS " << order.size();
            for (Dof dof : order)
            {
                out << " " << kChannelNames[static_cast<unsigned>(dof)];
                columns.push_back(dof);
                columnDofs.push_back(static_cast<unsigned>(def.getDofIndex(j, dof)));
            }
            out << "\n";
        }
        open.push_back(j);
    }
    while (!open.empty())
    {
        open.pop_back();
        out << std::string(2 * open.size(), ' ') << "}\n";
    }

    // No clip, no frames: what a reader reads back as a skeleton without motion.
    const unsigned numFrames = clip ? clip->getNumFrames() : 0;
    const double frameRate = clip ? clip->getFrameRate() : 1.0;
    out << "MOTION\nFrames: " << std::to_string(numFrames) << "\nFrame Time: "
        << formatInverse(frameRate, 1.0 / frameRate, frameRateOf) << "\n";
    std::string line;
    for (unsigned f = 0; f < numFrames; ++f)
    {
        line.clear();
        for (std::size_t c = 0; c < columns.size(); ++c)
        {
            const unsigned d = columnDofs[c];
            const double value = channelOf[d] >= 0 ? clip->getFrame(f)[channelOf[d]] : def.getDofDefault(d);
            if (c > 0) line += ' ';
            if (isRotation(columns[c])) line += formatDegrees(value);
            else appendNumber(line, value);
        }
        out << line << "\n";
    }
    if (!out)
    {
        error = "the output could not be written";
        return false;
    }
    return true;
}

} // namespace osgActor
