#include <osgActor/mocap/MocapImport>
#include <osgActor/mocap/TrajectoryCsv>
#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>
#include <osgActor/text/TextLines>

#include <cmath>
#include <fstream>

namespace osgActor {

namespace {

std::string_view trimmed(std::string_view text)
{
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
    return text;
}

std::vector<std::string_view> fields(std::string_view line)
{
    std::vector<std::string_view> result;
    std::size_t start = 0;
    while (true)
    {
        const std::size_t comma = line.find(',', start);
        result.push_back(
            trimmed(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
        if (comma == std::string_view::npos) return result;
        start = comma + 1;
    }
}

} // namespace

TrajectoryBuildResult readTrajectoryCsv(std::istream& in, const std::string& fileName, bool headingInDegrees)
{
    TextLines text(in, fileName);
    std::vector<TrajectoryKey> keys;
    auto failed = [&](const std::string& message) {
        TrajectoryBuildResult result;
        result.error = text.where() + message;
        return result;
    };
    if (!text.error().empty())
    {
        TrajectoryBuildResult result;
        result.error = text.error();
        return result;
    }
    const double angle = headingInDegrees ? kRadiansPerDegree : 1.0; // radiansFromDegrees()
    static const char* const kColumns[5] = {"time", "x", "y", "z", "heading"};
    bool first = true;
    while (text.nextLine())
    {
        const std::string_view line = trimmed(text.line());
        if (line.empty() || line.front() == '#') continue;
        const std::vector<std::string_view> f = fields(line);
        const bool isFirst = first;
        first = false;
        if (f.size() != 5)
            return failed(std::to_string(f.size()) + " fields; a point is time,x,y,z,heading");
        double values[5];
        bool numbers = true;
        for (unsigned i = 0; i < 5 && numbers; ++i) numbers = parseNumber(f[i], values[i]);
        if (!numbers && isFirst)
        {
            for (unsigned i = 0; i < 5; ++i)
                if (!sameWord(f[i], kColumns[i])) return failed("the header must be time,x,y,z,heading");
            continue;
        }
        for (unsigned i = 0; i < 5; ++i)
            if (!parseNumber(f[i], values[i])) return failed(std::string(kColumns[i]) + " " + numberProblem(f[i]));
        // The path places the actor (its pre-transform), which holds positions within +-kMaxDofMagnitude.
        for (unsigned i = 1; i < 4; ++i)
            if (std::abs(values[i]) > kMaxDofMagnitude)
                return failed(std::string(kColumns[i]) + " " + std::string(f[i]) +
                              " lies beyond what an actor holds (+-" + formatNumber(kMaxDofMagnitude) + ")");
        if (!keys.empty() && !(values[0] > keys.back().time))
            return failed("time " + std::string(f[0]) + " does not come after the line before");
        TrajectoryKey key;
        key.time = values[0];
        key.position = glm::dvec3(values[1], values[2], values[3]);
        key.heading = values[4] * angle;
        keys.push_back(key);
    }
    if (keys.empty()) return failed("the file holds no point");
    TrajectoryBuildResult result = TrajectoryBuilder::build(baseNameOf(fileName), std::move(keys));
    if (!result) result.error = fileName + ": " + result.error;
    return result;
}

TrajectoryBuildResult readTrajectoryCsvFile(const std::string& path, bool headingInDegrees)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        TrajectoryBuildResult failed;
        failed.error = path + ": cannot open the file";
        return failed;
    }
    return readTrajectoryCsv(in, path, headingInDegrees);
}

} // namespace osgActor
