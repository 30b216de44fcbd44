#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>

namespace osgActor {

namespace {

constexpr std::string_view kRadiansSuffix = "rad";

bool hasRadiansSuffix(std::string_view word)
{
    return word.size() >= kRadiansSuffix.size() && word.substr(word.size() - kRadiansSuffix.size()) == kRadiansSuffix;
}

std::string_view numberOf(std::string_view word)
{
    return hasRadiansSuffix(word) ? word.substr(0, word.size() - kRadiansSuffix.size()) : word;
}

} // namespace

std::string formatDegrees(double radians)
{
    return formatInverse(radians, radians * kDegreesPerRadian, radiansFromDegrees);
}

NumberWord readAngle(std::string_view word, double& radians)
{
    double value = 0.0;
    const NumberWord read = readNumber(numberOf(word), value);
    if (read == NumberWord::Finite) radians = hasRadiansSuffix(word) ? value : radiansFromDegrees(value);
    return read;
}

std::string angleProblem(std::string_view word)
{
    const std::string problem = numberProblem(numberOf(word));
    if (problem.empty() || !hasRadiansSuffix(word)) return problem;
    return "'" + std::string(word) + "': " + problem; // the number without its suffix is named
}

std::string formatAngle(double radians)
{
    std::string text;
    appendAngle(text, radians);
    return text;
}

void appendAngle(std::string& text, double radians)
{
    double degrees = 0.0;
    if (findExactInverse(radians, radians * kDegreesPerRadian, radiansFromDegrees, degrees))
    {
        appendNumber(text, degrees);
        return;
    }
    appendNumber(text, radians);
    text += kRadiansSuffix;
}

} // namespace osgActor
