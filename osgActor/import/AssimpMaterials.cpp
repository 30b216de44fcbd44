// The Assimp reader's materials (AssimpScene): the diffuse (or PBR base) colour and texture of each aiMaterial, and
// the images those textures show, embedded in the file or beside it.
#include "AssimpScene"

#include "ImageDecoding"

#include <assimp/material.h>

#include <cmath>
#include <fstream>
#include <iterator>

namespace osgActor {
namespace assimp {

namespace {

TextureWrap wrapOf(aiTextureMapMode mode)
{
    switch (mode)
    {
    case aiTextureMapMode_Clamp:
    case aiTextureMapMode_Decal: return TextureWrap::ClampToEdge;
    case aiTextureMapMode_Mirror: return TextureWrap::MirroredRepeat;
    default: return TextureWrap::Repeat;
    }
}

/** The bytes of a file, or none when it cannot be read. */
std::vector<unsigned char> readBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) return {};
    return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

class MaterialReader
{
public:
    explicit MaterialReader(SceneReading& reading) : _reading(reading) {}

    void read()
    {
        const aiScene& scene = _reading.scene;
        if (scene.mNumMaterials > 0 && !scene.mMaterials) throw Refusal("scene", "has no list of its materials");
        for (unsigned m = 0; m < scene.mNumMaterials; ++m)
        {
            if (!scene.mMaterials[m]) throw Refusal("materials[" + std::to_string(m) + "]", "is missing");
            _reading.model.materials.push_back(readMaterial(*scene.mMaterials[m], m));
        }
    }

private:
    RiggedMaterial readMaterial(const aiMaterial& source, unsigned index)
    {
        RiggedMaterial material;
        aiString name;
        if (source.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) material.name = name.C_Str();
        const std::string where = place("materials", index, name);
        aiColor4D colour(1.0f, 1.0f, 1.0f, 1.0f);
        if (source.Get(AI_MATKEY_BASE_COLOR, colour) != AI_SUCCESS) source.Get(AI_MATKEY_COLOR_DIFFUSE, colour);
        float opacity = 1.0f;
        source.Get(AI_MATKEY_OPACITY, opacity);
        if (!std::isfinite(colour.r) || !std::isfinite(colour.g) || !std::isfinite(colour.b) ||
            !std::isfinite(colour.a) || !std::isfinite(opacity))
        {
            _reading.warn(where + ": its colour is not finite; white is used");
            colour = aiColor4D(1.0f, 1.0f, 1.0f, 1.0f);
            opacity = 1.0f;
        }
        material.baseColorFactor = glm::dvec4(colour.r, colour.g, colour.b, colour.a * opacity);
        if (material.baseColorFactor.a < 1.0) material.alphaMode = AlphaMode::Blend;
        int twoSided = 0;
        if (source.Get(AI_MATKEY_TWOSIDED, twoSided) == AI_SUCCESS) material.doubleSided = twoSided != 0;
        readTexture(source, where, material.baseColorTexture);
        return material;
    }

    void readTexture(const aiMaterial& source, const std::string& where, RiggedTexture& texture)
    {
        aiTextureType type = aiTextureType_BASE_COLOR;
        if (source.GetTextureCount(type) == 0) type = aiTextureType_DIFFUSE;
        if (source.GetTextureCount(type) == 0) return;
        aiString path;
        unsigned uvIndex = 0;
        aiTextureMapMode modes[2] = {aiTextureMapMode_Wrap, aiTextureMapMode_Wrap};
        if (source.GetTexture(type, 0, &path, nullptr, &uvIndex, nullptr, nullptr, modes) != AI_SUCCESS) return;
        if (uvIndex > 1)
        {
            _reading.warn(where + ": its texture reads texture coordinate set " + std::to_string(uvIndex) +
                          ", which is not read; it is drawn untextured");
            return;
        }
        texture.image = image(path, where);
        texture.texCoord = uvIndex;
        texture.wrapS = wrapOf(modes[0]);
        texture.wrapT = wrapOf(modes[1]);
    }

    /** The index of the image a texture path names (decoded once for all materials), or -1 with a warning. */
    int image(const aiString& path, const std::string& where)
    {
        const std::string key = path.C_Str();
        const auto known = _images.find(key);
        if (known != _images.end()) return known->second;
        RiggedImage image;
        image.name = key;
        std::vector<unsigned char> bytes;
        const aiTexture* embedded = _reading.scene.GetEmbeddedTexture(path.C_Str());
        if (embedded && embedded->pcData)
        {
            if (embedded->mHeight == 0) // compressed: mWidth bytes of an image file
            {
                const auto* begin = reinterpret_cast<const unsigned char*>(embedded->pcData);
                bytes.assign(begin, begin + embedded->mWidth);
            }
            else // raw texels, BGRA, rows from the top
            {
                image.width = embedded->mWidth;
                image.height = embedded->mHeight;
                for (std::size_t t = 0; t < std::size_t(image.width) * image.height; ++t)
                    image.rgba.insert(image.rgba.end(), {embedded->pcData[t].r, embedded->pcData[t].g,
                                                         embedded->pcData[t].b, embedded->pcData[t].a});
            }
        }
        else
        {
            image.uri = key;
            bytes = readExternal(key);
            if (bytes.empty())
            {
                _reading.warn(where + ": its texture '" + key +
                              (_reading.folder.empty() ? "' is not read from memory" : "' is not found") +
                              "; it is drawn untextured");
                return _images[key] = -1;
            }
        }
        const int index = int(_reading.model.images.size());
        std::string error;
        if (image.rgba.empty() && !decodeImage(bytes.data(), bytes.size(), index, image, error))
        {
            _reading.warn(where + ": its texture '" + key + "' cannot be decoded (" + error +
                          "); it is drawn untextured");
            return _images[key] = -1;
        }
        _reading.model.images.push_back(std::move(image));
        return _images[key] = index;
    }

    /** An external texture's bytes: the path as written (Windows separators turned), relative to the model's folder
      * unless absolute, and else the file of that name in the model's folder (files moved from where they were
      * made: "D:\\textures\\skin.png" beside the model). */
    std::vector<unsigned char> readExternal(std::string path) const
    {
        if (_reading.folder.empty()) return {};
        for (char& c : path)
            if (c == '\\') c = '/';
        std::vector<unsigned char> bytes;
        if (!path.empty() && path[0] == '/') bytes = readBytes(path);
        else if (path.size() < 2 || path[1] != ':') bytes = readBytes(_reading.folder + path);
        if (!bytes.empty()) return bytes;
        const std::size_t slash = path.find_last_of('/');
        return readBytes(_reading.folder + (slash == std::string::npos ? path : path.substr(slash + 1)));
    }

    SceneReading& _reading;
    std::map<std::string, int> _images;
};

} // namespace

void readMaterials(SceneReading& reading) { MaterialReader(reading).read(); }

} // namespace assimp
} // namespace osgActor
