// libFuzzer target: the trajectory csv parser on arbitrary bytes (fuzz/ParserContract says what it must do).
#include "FuzzMain"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    osgActor::fuzz::require(osgActor::contract::checkTrajectoryCsv(osgActor::fuzz::text(data, size)));
    return 0;
}
