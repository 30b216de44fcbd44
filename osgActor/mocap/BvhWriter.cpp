#include <osgActor/mocap/BvhWriter>

#include <glm/ext/scalar_constants.hpp>

#include <cstdio>
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

std::string formatNumber(double value)
{
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.10g", value == 0.0 ? 0.0 : value); // no "-0"
    return buffer;
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
        if (std::abs(std::abs(q.w) - 1.0) > 1e-12)
        {
            error = "joint '" + def.getJointName(j) + "' has an offset rotation, which BVH cannot express";
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
        const bool endSite = def.getDofMask(j) == 0 && numChildren[j] == 0 && def.getParent(j) >= 0;
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

    const unsigned numFrames = clip ? clip->getNumFrames() : 1;
    out << "MOTION\nFrames: " << numFrames << "\nFrame Time: " << formatNumber(clip ? 1.0 / clip->getFrameRate() : 1.0)
        << "\n";
    const double toDegrees = 180.0 / glm::pi<double>();
    std::string line;
    for (unsigned f = 0; f < numFrames; ++f)
    {
        line.clear();
        for (std::size_t c = 0; c < columns.size(); ++c)
        {
            const unsigned d = columnDofs[c];
            const double value = channelOf[d] >= 0 ? clip->getFrame(f)[channelOf[d]] : def.getDofDefault(d);
            if (c > 0) line += ' ';
            line += formatNumber(isRotation(columns[c]) ? value * toDegrees : value);
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
