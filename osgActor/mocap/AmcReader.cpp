#include <osgActor/mocap/AmcReader>
#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>
#include <osgActor/text/TextLines>

#include <osgActor/core/ClipBuilder>

#include <algorithm>
#include <fstream>
#include <limits>
#include <unordered_map>

namespace osgActor {

MocapImport readAmc(std::istream& in, const std::string& fileName, const AsfImport& skeleton,
                    const std::string& clipName)
{
    MocapImport result;
    if (!skeleton.definition)
    {
        result.error = fileName + ": the ASF skeleton was not read";
        return result;
    }
    const ActorDefinition& def = *skeleton.definition;
    std::unordered_map<std::string, const AsfAmcLayout*> layouts;
    for (const AsfAmcLayout& layout : skeleton.layouts) layouts.emplace(layout.bone, &layout);

    TextLines text(in, fileName);
    auto failed = [&](const std::string& message) {
        MocapImport error;
        error.error = text.where() + message;
        return error;
    };
    if (!text.error().empty())
    {
        result.error = text.error();
        return result;
    }
    const unsigned numDofs = def.getNumDofs();
    bool degrees = skeleton.degrees;
    std::vector<double> values;    // frame-major, numDofs per frame
    unsigned long numFrames = 0;
    unsigned long lastFrameNumber = 0; // as the file numbers frames
    unsigned linesInFrame = 0;
    unsigned long incompleteFrames = 0;
    auto endFrame = [&]() {
        if (numFrames > 0 && linesInFrame < skeleton.layouts.size()) ++incompleteFrames;
    };
    while (text.nextLine())
    {
        const std::vector<std::string_view>& t = text.tokens();
        if (t.empty() || t[0].front() == '#') continue;
        if (t[0].front() == ':')
        {
            if (sameWord(t[0], ":DEGREES")) degrees = true;
            else if (sameWord(t[0], ":RADIANS")) degrees = false;
            continue; // :FULLY-SPECIFIED and others
        }
        unsigned long frameNumber;
        if (t.size() == 1 && parseCount(t[0], frameNumber))
        {
            // Frames are stored one after the other at the frame rate: a frame missing, repeated or out of order
            // would move every later one in time, so the numbers must count up by one from the first.
            if (numFrames > 0 && (lastFrameNumber == std::numeric_limits<unsigned long>::max() ||
                                  frameNumber != lastFrameNumber + 1))
                return failed("frame number " + std::string(t[0]) + " follows frame " +
                              std::to_string(lastFrameNumber) + "; AMC frames must be numbered one after the other");
            lastFrameNumber = frameNumber;
            endFrame();
            // A new frame starts from the previous one, so a bone left out keeps its values.
            if (numFrames == 0) values.assign(def.getDefaultDofs().begin(), def.getDefaultDofs().end());
            else
            {
                values.resize(values.size() + numDofs);
                std::copy(values.end() - 2 * numDofs, values.end() - numDofs, values.end() - numDofs);
            }
            ++numFrames;
            linesInFrame = 0;
            continue;
        }
        if (numFrames == 0) return failed("'" + std::string(t[0]) + "' comes before the first frame number");
        const auto found = layouts.find(std::string(t[0]));
        if (found == layouts.end())
            return failed("unknown bone '" + std::string(t[0]) + "' (not a bone with dofs in the ASF skeleton)");
        const AsfAmcLayout& layout = *found->second;
        if (t.size() - 1 != layout.dofs.size())
            return failed("bone '" + layout.bone + "' has " + std::to_string(t.size() - 1) +
                          " values; its dof list has " + std::to_string(layout.dofs.size()));
        double* row = values.data() + (numFrames - 1) * numDofs;
        const double angle = degrees ? kRadiansPerDegree : 1.0; // radiansFromDegrees()
        bool hasTranslation = false;
        glm::dvec3 translation(0.0); // file units and axes; a component the line leaves out is 0
        for (std::size_t i = 0; i < layout.dofs.size(); ++i)
        {
            double value;
            if (!parseNumber(t[i + 1], value))
                return failed("value " + std::to_string(i + 1) + " of bone '" + layout.bone + "': " +
                              numberProblem(t[i + 1]));
            if (layout.angular[i]) row[layout.dofs[i]] = value * angle;
            else
            {
                translation[layout.translationAxis[i]] = value;
                hasTranslation = true;
            }
        }
        if (hasTranslation)
        {
            // Onto the joint's translation DOFs, in model units (see AsfAmcLayout::translationMap).
            const glm::dvec3 mapped = layout.translationMap * translation;
            for (std::size_t i = 0; i < layout.dofs.size(); ++i)
                if (!layout.angular[i]) row[layout.dofs[i]] = mapped[layout.translationAxis[i]];
        }
        ++linesInFrame;
    }
    endFrame();
    if (numFrames == 0) return failed("the file holds no frame");
    if (incompleteFrames > 0)
        result.warnings.push_back(fileName + ": " + std::to_string(incompleteFrames) +
                                  " frames leave out some bones; those keep their previous values");
    result.definition = skeleton.definition;
    if (numDofs == 0) return result;
    ClipBuilder clip(clipName.empty() ? baseNameOf(fileName) : clipName);
    for (unsigned d = 0; d < numDofs; ++d) clip.addChannel(def.getDofName(d), skeleton.options.interpolation);
    clip.setFrames(skeleton.options.frameRate, std::move(values));
    const ClipBuildResult built = clip.build();
    if (!built)
    {
        MocapImport error;
        error.error = fileName + ": " + built.error;
        return error;
    }
    result.clip = built.clip;
    return result;
}

MocapImport readAmcFile(const std::string& path, const AsfImport& skeleton, const std::string& clipName)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        MocapImport failed;
        failed.error = path + ": cannot open the file";
        return failed;
    }
    return readAmc(in, path, skeleton, clipName);
}

} // namespace osgActor
