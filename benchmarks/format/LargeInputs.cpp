#include "LargeInputs"

#include <osgActor/core/ActorDefinitionBuilder>

#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace bench {

namespace {

std::string readMocapFile(const std::string& relativePath)
{
    const std::string path = std::string(OSGACTOR_BENCH_MOCAP_DIR) + "/" + relativePath;
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/** The text's lines, without their line ends (CMU's files end lines with CR LF). */
std::vector<std::string> linesOf(const std::string& text)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
    {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back(line);
    }
    return lines;
}

bool isFrameNumber(const std::string& line)
{
    if (line.empty()) return false;
    for (char c : line)
        if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    return true;
}

} // namespace

const char* shapeName(SkeletonShape shape) { return shape == SkeletonShape::Wide ? "wide" : "deep"; }

std::string largeActorText(SkeletonShape shape, unsigned joints)
{
    std::string text = "osgactor 1\nactor large {\n    joint j0 { dof rx }\n";
    // Below the root, a chain restarts at the root every `chain` joints: the root and one chain are kMaxJointDepth.
    const unsigned chain = shape == SkeletonShape::Wide ? 1u : osgActor::kMaxJointDepth - 1u;
    for (unsigned j = 1; j < joints; ++j)
    {
        const unsigned parent = (j - 1) % chain == 0 ? 0u : j - 1;
        text += "    joint j" + std::to_string(j) + " { parent j" + std::to_string(parent) +
                "; offset 0.1 0 0; dof rz }\n";
    }
    return text + "}\n";
}

std::string longBvhText(unsigned frames)
{
    static const std::string source = readMocapFile("bvh/12_03.bvh");
    const std::size_t motion = source.find("MOTION");
    const std::vector<std::string> lines = linesOf(source.substr(motion));
    // lines[0] "MOTION", [1] "Frames: n", [2] "Frame Time: t", then one frame a line.
    std::vector<std::string> data(lines.begin() + 3, lines.end());
    while (!data.empty() && data.back().empty()) data.pop_back();
    std::string text = source.substr(0, motion) + "MOTION\nFrames: " + std::to_string(frames) + "\n" + lines[2] + "\n";
    for (unsigned f = 0; f < frames; ++f) text += data[f % data.size()] + "\n";
    return text;
}

const std::string& amcSkeletonText()
{
    static const std::string text = readMocapFile("asfamc/11.asf");
    return text;
}

std::string longAmcText(unsigned frames)
{
    static const std::string source = readMocapFile("asfamc/11_01.amc");
    const std::vector<std::string> lines = linesOf(source);
    // The header (comments and keywords), then for each frame its number on a line and one line a bone.
    std::string header;
    std::vector<std::string> bodies;
    for (const std::string& line : lines)
    {
        if (isFrameNumber(line)) bodies.emplace_back();
        else if (bodies.empty()) header += line + "\n";
        else if (!line.empty()) bodies.back() += line + "\n";
    }
    std::string text = header;
    for (unsigned f = 0; f < frames; ++f) text += std::to_string(f + 1) + "\n" + bodies[f % bodies.size()];
    return text;
}

} // namespace bench
