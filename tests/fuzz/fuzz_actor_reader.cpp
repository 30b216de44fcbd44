// libFuzzer target: any bytes through the .actor reader and, when they read, through the writer and the reader
// again. It must never crash, never hand back a half-built result, and a written file must read back and write
// to the same text.
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>

#include <cstdint>
#include <cstdlib>
#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    const osgActor::ActorReadResult result = osgActor::readActor(in, "fuzz.actor");
    if (!result)
    {
        if (result.error.rfind("fuzz.actor:", 0) != 0 || !result.document.joints.empty()) std::abort();
        return 0;
    }
    std::ostringstream first;
    osgActor::writeActor(first, result.document);
    std::istringstream again(first.str());
    const osgActor::ActorReadResult reread = osgActor::readActor(again, "written.actor");
    if (!reread) std::abort();
    std::ostringstream second;
    osgActor::writeActor(second, reread.document);
    if (second.str() != first.str()) std::abort();
    return 0;
}
