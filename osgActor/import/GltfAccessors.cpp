#include "GltfAccessors"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace osgActor {
namespace gltf {

namespace {

unsigned componentsOf(int type)
{
    switch (type)
    {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
    }
}

unsigned sizeOf(int componentType)
{
    switch (componentType)
    {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

/** One little-endian component at bytes, decoded as the accessor says. */
double decode(const unsigned char* bytes, int componentType, bool normalized)
{
    switch (componentType)
    {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
    {
        float f;
        std::memcpy(&f, bytes, 4);
        return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? bytes[0] / 255.0 : bytes[0];
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    {
        const double c = static_cast<signed char>(bytes[0]);
        return normalized ? std::max(c / 127.0, -1.0) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
    {
        const double c = bytes[0] | (bytes[1] << 8);
        return normalized ? c / 65535.0 : c;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    {
        const double c = static_cast<std::int16_t>(bytes[0] | (bytes[1] << 8));
        return normalized ? std::max(c / 32767.0, -1.0) : c;
    }
    default: // UNSIGNED_INT
        return static_cast<double>(std::uint32_t(bytes[0]) | (std::uint32_t(bytes[1]) << 8) |
                                   (std::uint32_t(bytes[2]) << 16) | (std::uint32_t(bytes[3]) << 24));
    }
}

/** The bytes of a buffer view, checked to lie within its buffer. */
const tinygltf::BufferView& checkedView(const tinygltf::Model& model, int viewIndex, const std::string& where)
{
    if (viewIndex < 0 || std::size_t(viewIndex) >= model.bufferViews.size())
        throw Refusal(where, "bufferView " + std::to_string(viewIndex) + " does not exist");
    const tinygltf::BufferView& view = model.bufferViews[viewIndex];
    const std::string viewPlace = "bufferViews[" + std::to_string(viewIndex) + "]";
    if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size())
        throw Refusal(viewPlace, "buffer " + std::to_string(view.buffer) + " does not exist");
    const std::size_t bufferSize = model.buffers[view.buffer].data.size();
    if (view.byteOffset > bufferSize || view.byteLength > bufferSize - view.byteOffset)
        throw Refusal(viewPlace, "bytes " + std::to_string(view.byteOffset) + " to " +
                                     std::to_string(view.byteOffset + view.byteLength) + " reach past the end of buffers[" +
                                     std::to_string(view.buffer) + "] (" + std::to_string(bufferSize) +
                                     " bytes: missing or short)");
    return view;
}

/** Where count elements of elementSize bytes start in a buffer view, and their stride; refuses elements that reach
  * past the view, or a view that reaches past its buffer. */
struct ElementRange
{
    const unsigned char* base;
    std::size_t stride;
};

ElementRange checkedElements(const tinygltf::Model& model, int viewIndex, std::size_t byteOffset, std::size_t count,
                             std::size_t elementSize, const std::string& where)
{
    const tinygltf::BufferView& view = checkedView(model, viewIndex, where);
    const std::size_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
    if (view.byteStride != 0 && view.byteStride < elementSize)
        throw Refusal(where, "byteStride " + std::to_string(view.byteStride) + " is smaller than one element (" +
                                 std::to_string(elementSize) + " bytes)");
    if (count > 0 && (byteOffset > view.byteLength || (count - 1) > (view.byteLength - byteOffset) / stride ||
                      (count - 1) * stride + elementSize > view.byteLength - byteOffset))
        throw Refusal(where, std::to_string(count) + " elements from byte " + std::to_string(byteOffset) +
                                 " reach past the end of bufferViews[" + std::to_string(viewIndex) + "] (" +
                                 std::to_string(view.byteLength) + " bytes)");
    return ElementRange{model.buffers[view.buffer].data.data() + view.byteOffset + byteOffset, stride};
}

/** Decodes count elements of a checked range into out, components numbers each. */
void decodeElements(const ElementRange& range, std::size_t count, unsigned components, int componentType,
                    bool normalized, double* out)
{
    const unsigned componentSize = sizeOf(componentType);
    for (std::size_t e = 0; e < count; ++e)
        for (unsigned c = 0; c < components; ++c)
            out[e * components + c] = decode(range.base + e * range.stride + c * componentSize, componentType,
                                             normalized);
}

} // namespace

std::string accessorPlace(int index, const AccessorRule& rule, const std::string& place)
{
    return "accessors[" + std::to_string(index) + "] (" + rule.role + " of " + place + ")";
}

AccessorData readAccessor(const tinygltf::Model& model, int index, const AccessorRule& rule, const std::string& place)
{
    if (index < 0 || std::size_t(index) >= model.accessors.size())
        throw Refusal(place, std::string(rule.role) + " names accessor " + std::to_string(index) + ", which does not exist");
    const tinygltf::Accessor& accessor = model.accessors[index];
    const std::string where = accessorPlace(index, rule, place);
    if (std::find(rule.types.begin(), rule.types.end(), accessor.type) == rule.types.end())
        throw Refusal(where, "element type " + std::to_string(accessor.type) + " is not one this use accepts");
    if (std::find(rule.componentTypes.begin(), rule.componentTypes.end(), accessor.componentType) ==
        rule.componentTypes.end())
        throw Refusal(where, "component type " + std::to_string(accessor.componentType) + " is not one this use accepts");
    const bool isFloat = accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
    if (!isFloat && accessor.normalized != rule.integersNormalized)
        throw Refusal(where, rule.integersNormalized ? "integer components must be normalized here"
                                                     : "integer components must not be normalized here");

    AccessorData data;
    data.count = accessor.count;
    data.components = componentsOf(accessor.type);
    const std::size_t elementSize = std::size_t(data.components) * sizeOf(accessor.componentType);
    const bool normalized = !isFloat && accessor.normalized;
    // Every range is checked before anything is allocated, so no allocation is larger than the bytes behind it
    // (bounded by the file's size), except a sparse-only accessor's zeros, bounded here.
    ElementRange dense{nullptr, 0};
    if (accessor.bufferView >= 0)
        dense = checkedElements(model, accessor.bufferView, accessor.byteOffset, accessor.count, elementSize, where);
    else if (!accessor.sparse.isSparse && accessor.count > 0)
        throw Refusal(where, "has neither a bufferView nor sparse values");
    else if (accessor.count > (std::size_t(1) << 20))
        throw Refusal(where, "a sparse accessor of " + std::to_string(accessor.count) + " elements is too large");
    data.values.assign(accessor.count * data.components, 0.0);
    if (dense.base) decodeElements(dense, accessor.count, data.components, accessor.componentType, normalized,
                                   data.values.data());

    if (accessor.sparse.isSparse)
    {
        const auto& sparse = accessor.sparse;
        if (sparse.count < 0 || std::size_t(sparse.count) > accessor.count)
            throw Refusal(where, "sparse count " + std::to_string(sparse.count) + " is out of range");
        const int indexType = sparse.indices.componentType;
        if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            throw Refusal(where, "sparse indices must be unsigned integers");
        if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
            throw Refusal(where, "sparse byteOffset is negative");
        const ElementRange indexRange = checkedElements(model, sparse.indices.bufferView, sparse.indices.byteOffset,
                                                        sparse.count, sizeOf(indexType), where + " sparse indices");
        const ElementRange valueRange = checkedElements(model, sparse.values.bufferView, sparse.values.byteOffset,
                                                        sparse.count, elementSize, where + " sparse values");
        std::vector<double> indices(sparse.count);
        std::vector<double> values(std::size_t(sparse.count) * data.components);
        decodeElements(indexRange, sparse.count, 1, indexType, false, indices.data());
        decodeElements(valueRange, sparse.count, data.components, accessor.componentType, normalized, values.data());
        for (int s = 0; s < sparse.count; ++s)
        {
            if (indices[s] >= double(accessor.count))
                throw Refusal(where, "sparse index " + std::to_string(std::size_t(indices[s])) + " is out of range (" +
                                         std::to_string(accessor.count) + " elements)");
            std::copy_n(values.begin() + std::size_t(s) * data.components, data.components,
                        data.values.begin() + std::size_t(indices[s]) * data.components);
        }
    }

    if (isFloat)
        for (std::size_t i = 0; i < data.values.size(); ++i)
            if (!std::isfinite(data.values[i]))
                throw Refusal(where, "element " + std::to_string(i / data.components) + " holds a number that is not "
                                         "finite (" + std::to_string(data.values[i]) + ")");
    return data;
}

} // namespace gltf
} // namespace osgActor
