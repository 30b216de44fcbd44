// libFuzzer target: the asf parser on arbitrary bytes (fuzz/ParserContract says what it must do).
#include "FuzzMain"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    osgActor::fuzz::require(osgActor::contract::checkAsf(osgActor::fuzz::text(data, size)));
    return 0;
}
