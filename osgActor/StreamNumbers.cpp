#include <osgActor/StreamNumbers>
#include <osgActor/text/Numbers>

#include <cmath>

namespace osgActor {

void writeStreamNumber(osgDB::OutputStream& os, double value)
{
    if (os.isBinary())
        os << value;
    else
        os << formatNumber(value);
}

bool readStreamNumber(osgDB::InputStream& is, double& value, const std::string& what)
{
    if (is.isBinary())
    {
        double read = 0.0;
        is >> read;
        if (is.getException()) return false;
        if (std::isfinite(read))
        {
            value = read;
            return true;
        }
        is.throwException("osgActor: " + what + ": " + formatNumber(read) + " is not a finite number");
        return false;
    }
    std::string word;
    is >> word;
    if (is.getException()) return false;
    if (parseNumber(word, value)) return true;
    is.throwException("osgActor: " + what + ": " + numberProblem(word));
    return false;
}

} // namespace osgActor
