// libFuzzer target: the AMC parser on arbitrary bytes, against one real ASF skeleton read once at start
// (OSGACTOR_FUZZ_ASF, else the CMU skeleton in data/mocap).
#include "FuzzMain"

namespace {
osgActor::AsfImport skeleton;
}

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    const char* path = std::getenv("OSGACTOR_FUZZ_ASF");
    skeleton = osgActor::readAsfFile(path ? path : OSGACTOR_FUZZ_DEFAULT_ASF);
    if (!skeleton)
    {
        std::fprintf(stderr, "fuzz_amc: no skeleton: %s\n", skeleton.error.c_str());
        std::exit(1);
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    osgActor::fuzz::require(osgActor::contract::checkAmc(osgActor::fuzz::text(data, size), skeleton));
    return 0;
}
