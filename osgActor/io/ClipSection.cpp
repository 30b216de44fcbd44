#include <osgActor/io/ActorNumbers>
#include <osgActor/io/ClipSection>

#include <glm/ext/scalar_constants.hpp>

#include <map>

namespace osgActor {

namespace {

const char* const kInterpolationNames[] = {"step", "linear", "cubic"};
const char* const kPlayModeNames[] = {"once", "loop", "pingpong"};

SyntaxArgument word(const std::string& text, bool quote = false)
{
    SyntaxArgument argument;
    argument.text = text;
    argument.quoted = quote;
    return argument;
}

SyntaxStatement statement(const std::string& keyword) { SyntaxStatement s; s.keyword = keyword; return s; }

/** File value of a channel value: degrees for rotations. */
double toFile(const ClipChannel& channel, double value) { return channel.angular ? value * 180.0 / glm::pi<double>() : value; }
double fromFile(const ClipChannel& channel, double value) { return channel.angular ? value * glm::pi<double>() / 180.0 : value; }

} // namespace

SyntaxStatement clipToSection(const Clip& clip)
{
    SyntaxStatement section = statement("clip");
    section.arguments.push_back(word(clip.getName(), quoteIfNeeded(clip.getName()) != clip.getName()));
    section.hasBlock = true;
    const Interpolation interpolation = clip.getNumChannels() > 0 ? clip.getChannel(0).interpolation : Interpolation::Linear;
    SyntaxStatement mode = statement("interpolation");
    mode.arguments.push_back(word(kInterpolationNames[static_cast<unsigned>(interpolation)]));
    section.children.push_back(mode);
    if (clip.isUniform())
    {
        SyntaxStatement rate = statement("rate");
        rate.arguments.push_back(word(formatNumber(clip.getFrameRate())));
        section.children.push_back(rate);
        SyntaxStatement channels = statement("channels");
        for (unsigned c = 0; c < clip.getNumChannels(); ++c)
        {
            const std::string& target = clip.getChannel(c).target;
            channels.arguments.push_back(word(target, quoteIfNeeded(target) != target));
        }
        section.children.push_back(channels);
        for (unsigned f = 0; f < clip.getNumFrames(); ++f)
        {
            SyntaxStatement frame = statement("frame");
            for (unsigned c = 0; c < clip.getNumChannels(); ++c)
                frame.arguments.push_back(word(formatNumber(toFile(clip.getChannel(c), clip.getFrame(f)[c]))));
            section.children.push_back(frame);
        }
        return section;
    }
    for (unsigned c = 0; c < clip.getNumChannels(); ++c)
        for (unsigned k = 0; k < clip.getNumKeys(c); ++k)
        {
            SyntaxStatement key = statement("key");
            key.arguments.push_back(word(formatNumber(clip.getKeyTime(c, k))));
            key.arguments.push_back(word(clip.getChannel(c).target, true));
            key.arguments.push_back(word(formatNumber(toFile(clip.getChannel(c), clip.getKeyValue(c, k)))));
            section.children.push_back(key);
        }
    return section;
}

SyntaxStatement clipToSection(const Clip& clip, PlayMode play)
{
    SyntaxStatement section = clipToSection(clip);
    SyntaxStatement statement;
    statement.keyword = "play";
    statement.arguments.push_back(word(kPlayModeNames[static_cast<unsigned>(play)]));
    section.children.insert(section.children.begin(), statement);
    return section;
}

bool clipSectionPlays(const SyntaxStatement& section, PlayMode& mode)
{
    for (const SyntaxStatement& s : section.children)
        if (s.keyword == "play" && s.arguments.size() == 1)
            for (unsigned i = 0; i < 3; ++i)
                if (s.arguments[0].text == kPlayModeNames[i])
                {
                    mode = static_cast<PlayMode>(i);
                    return true;
                }
    return false;
}

ClipBuildResult clipFromSection(const SyntaxStatement& section, const std::string& fileName)
{
    ClipBuildResult result;
    auto fail = [&](int line, const std::string& message) {
        result.clip.reset();
        result.error = fileName + ":" + std::to_string(line) + ": " + message;
        return result;
    };
    if (section.keyword != "clip" || section.arguments.size() != 1 || !section.hasBlock)
        return fail(section.line, "a clip is written 'clip name { ... }'");
    ClipBuilder builder(section.arguments[0].text);
    Interpolation interpolation = Interpolation::Linear;
    double rate = 0.0;
    std::vector<double> frames;
    std::map<std::string, unsigned> keyedChannels;
    std::vector<ClipChannel> channels; // as the builder will hold them, for degree conversion
    auto number = [&](const SyntaxArgument& argument, double& value) {
        return parseNumber(argument.text, value) && !argument.quoted;
    };
    for (const SyntaxStatement& s : section.children)
    {
        if (s.keyword == "play")
        {
            PlayMode mode;
            SyntaxStatement alone;
            alone.children.push_back(s);
            if (!clipSectionPlays(alone, mode)) return fail(s.line, "play must be once, loop or pingpong");
        }
        else if (s.keyword == "interpolation")
        {
            bool known = false;
            for (unsigned i = 0; i < 3; ++i)
                if (s.arguments.size() == 1 && s.arguments[0].text == kInterpolationNames[i])
                {
                    interpolation = static_cast<Interpolation>(i);
                    known = true;
                }
            if (!known) return fail(s.line, "interpolation must be step, linear or cubic");
        }
        else if (s.keyword == "rate")
        {
            if (s.arguments.size() != 1 || !number(s.arguments[0], rate)) return fail(s.line, "rate needs a number");
        }
        else if (s.keyword == "channels")
        {
            for (const SyntaxArgument& a : s.arguments)
            {
                builder.addChannel(a.text, interpolation);
                ClipChannel channel;
                channel.target = a.text;
                const std::size_t dot = a.text.rfind('.');
                Dof dof;
                channel.angular = dot != std::string::npos && parseDof(a.text.substr(dot + 1), dof) && isRotation(dof);
                channels.push_back(channel);
            }
        }
        else if (s.keyword == "frame")
        {
            if (s.arguments.size() != channels.size())
                return fail(s.line, "a frame has " + std::to_string(s.arguments.size()) + " values for " +
                                        std::to_string(channels.size()) + " channels");
            for (std::size_t c = 0; c < channels.size(); ++c)
            {
                double value;
                if (!number(s.arguments[c], value))
                    return fail(s.line, "'" + s.arguments[c].text + "' is not a finite number");
                frames.push_back(fromFile(channels[c], value));
            }
        }
        else if (s.keyword == "key")
        {
            double time, value;
            if (s.arguments.size() != 3 || !number(s.arguments[0], time) || !number(s.arguments[2], value))
                return fail(s.line, "a key is written 'key time \"joint.dof\" value'");
            const std::string& target = s.arguments[1].text;
            auto found = keyedChannels.find(target);
            if (found == keyedChannels.end())
            {
                found = keyedChannels.emplace(target, builder.addChannel(target, interpolation)).first;
                ClipChannel channel;
                const std::size_t dot = target.rfind('.');
                Dof dof;
                channel.angular = dot != std::string::npos && parseDof(target.substr(dot + 1), dof) && isRotation(dof);
                channels.push_back(channel);
            }
            builder.addKey(found->second, time, fromFile(channels[found->second], value));
        }
        else
            return fail(s.line, "unknown clip statement '" + s.keyword + "'");
    }
    if (!frames.empty() || rate > 0.0)
    {
        if (!keyedChannels.empty()) return fail(section.line, "a clip has either frames or keys, not both");
        builder.setFrames(rate, std::move(frames));
    }
    result = builder.build();
    if (!result) return fail(section.line, result.error);
    return result;
}

} // namespace osgActor
