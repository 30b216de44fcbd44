#include "ScratchFolder.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

namespace osgActorRender {

ScratchFolder::~ScratchFolder()
{
    if (_path.empty()) return;
    std::error_code ignored; // a folder left behind in the temporary directory is no reason to fail the run
    std::filesystem::remove_all(_path, ignored);
}

bool ScratchFolder::create(std::string& error)
{
    const char* tmp = std::getenv("TMPDIR");
    std::string templ = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/osgactorrender-XXXXXX";
    std::vector<char> name(templ.begin(), templ.end());
    name.push_back('\0');
    if (mkdtemp(name.data()) == nullptr)
    {
        error = "cannot make a temporary folder like " + templ + ": " + std::strerror(errno);
        return false;
    }
    _path = name.data();
    return true;
}

} // namespace osgActorRender
