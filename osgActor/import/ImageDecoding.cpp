#include "ImageDecoding"

#include <tiny_gltf.h>

#include <algorithm>
#include <limits>

namespace osgActor {

bool decodeImage(const unsigned char* bytes, std::size_t size, int index, RiggedImage& image, std::string& error)
{
    if (size == 0)
    {
        error = "no bytes";
        return false;
    }
    if (size > std::size_t(std::numeric_limits<int>::max()))
    {
        error = "too large";
        return false;
    }
    tinygltf::Image decoded;
    std::string warning;
    error.clear();
    if (!tinygltf::LoadImageData(&decoded, index, &error, &warning, 0, 0, bytes, int(size), nullptr) ||
        decoded.width <= 0 || decoded.height <= 0 || decoded.component != 4 || decoded.bits != 8 ||
        decoded.image.size() != std::size_t(decoded.width) * decoded.height * 4)
    {
        while (!error.empty() && (error.back() == '\n' || error.back() == '\r')) error.pop_back();
        std::replace(error.begin(), error.end(), '\n', ';');
        if (error.empty()) error = "not an 8-bit image the decoder reads";
        return false;
    }
    image.width = unsigned(decoded.width);
    image.height = unsigned(decoded.height);
    image.rgba = std::move(decoded.image);
    return true;
}

} // namespace osgActor
