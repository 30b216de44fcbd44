// libFuzzer target: the bvh parser on arbitrary bytes (fuzz/ParserContract says what it must do).
#include "FuzzMain"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    osgActor::fuzz::require(osgActor::contract::checkBvh(osgActor::fuzz::text(data, size)));
    return 0;
}
