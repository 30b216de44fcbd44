// libFuzzer target: the .actor reader on arbitrary bytes, and the writer on what it reads (fuzz/ParserContract).
#include "FuzzMain"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    osgActor::fuzz::require(osgActor::contract::checkActor(osgActor::fuzz::text(data, size)));
    return 0;
}
