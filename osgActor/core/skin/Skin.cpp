#include <osgActor/core/skin/Skin>

namespace osgActor {

SkinVertices SkinVertices::subrange(std::size_t first, std::size_t count) const
{
    SkinVertices piece;
    piece.positions = positions.subspan(first, count);
    if (!normals.empty()) piece.normals = normals.subspan(first, count);
    if (!tangents.empty()) piece.tangents = tangents.subspan(first, count);
    piece.outputIndices = outputIndices.subspan(first, count);

    // Walk the groups in order: skip `first` vertices, then take `count`, and find where the piece's influences
    // start and end in joints and weights.
    std::size_t toSkip = first;
    std::size_t toTake = count;
    std::size_t influenceBegin = 0;
    std::size_t influenceCount = 0;
    for (unsigned k = 1; k <= kMaxSkinInfluences; ++k)
    {
        const std::size_t inGroup = counts[k - 1];
        const std::size_t skipped = toSkip < inGroup ? toSkip : inGroup;
        toSkip -= skipped;
        influenceBegin += skipped * k;
        const std::size_t left = inGroup - skipped;
        const std::size_t taken = toTake < left ? toTake : left;
        toTake -= taken;
        influenceCount += taken * k;
        piece.counts[k - 1] = static_cast<std::uint32_t>(taken);
        if (toSkip == 0 && toTake == 0) break;
    }
    // Once the skipping is over, the influences taken follow on directly from influenceBegin, since the groups
    // are consecutive.
    piece.joints = joints.subspan(influenceBegin, influenceCount);
    piece.weights = weights.subspan(influenceBegin, influenceCount);
    return piece;
}

SkinVertices Skin::getVertices() const
{
    SkinVertices vertices;
    vertices.positions = _positions;
    vertices.normals = _normals;
    vertices.tangents = _tangents;
    vertices.outputIndices = _fileOrder;
    vertices.joints = _joints;
    vertices.weights = _weights;
    for (unsigned k = 0; k < kMaxSkinInfluences; ++k) vertices.counts[k] = _groupCounts[k];
    return vertices;
}

} // namespace osgActor
