#include <osgActor/mocap/PositionsCsv>

#include <osgActor/core/ActorPose>
#include <osgActor/text/Numbers>

#include <algorithm>
#include <vector>

namespace osgActor {

namespace {

std::string csvField(const std::string& text)
{
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

} // namespace

bool writePositionsCsv(std::ostream& out, const ActorDefinitionPtr& definition, const Clip& clip, unsigned firstFrame,
                       unsigned endFrame, std::string& error)
{
    if (!clip.isUniform())
    {
        error = "clip '" + clip.getName() + "' is keyed; positions are written per stored frame";
        return false;
    }
    endFrame = std::min(endFrame, clip.getNumFrames());
    if (firstFrame >= endFrame)
    {
        error = "the frame range is empty (the clip has " + std::to_string(clip.getNumFrames()) + " frames)";
        return false;
    }
    // The clip's channel for each DOF (importers write them in DOF order, but any clip of the actor works).
    std::vector<int> channelOf(definition->getNumDofs());
    for (unsigned d = 0; d < definition->getNumDofs(); ++d) channelOf[d] = clip.findChannel(definition->getDofName(d));
    std::vector<std::string> names;
    for (unsigned j = 0; j < definition->getNumJoints(); ++j) names.push_back(csvField(definition->getJointName(j)));

    ActorPose pose(definition);
    out << "frame,joint,x,y,z\n";
    std::string row;
    for (unsigned f = firstFrame; f < endFrame; ++f)
    {
        const double* values = clip.getFrame(f);
        for (unsigned d = 0; d < definition->getNumDofs(); ++d)
            if (channelOf[d] >= 0) pose.setDof(d, values[channelOf[d]]);
        pose.updateMatrices();
        for (unsigned j = 0; j < definition->getNumJoints(); ++j)
        {
            const glm::dvec4& p = pose.getModelMatrix(j)[3];
            row = std::to_string(f) + ',' + names[j];
            for (const double coordinate : {p.x, p.y, p.z})
            {
                row += ',';
                appendNumber(row, coordinate);
            }
            row += '\n';
            out << row;
        }
    }
    if (!out)
    {
        error = "the output could not be written";
        return false;
    }
    return true;
}

} // namespace osgActor
