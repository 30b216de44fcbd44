#include <osgActor/Offscreen/ContactSheet>

#include <algorithm>
#include <cmath>

namespace osgActor {

ContactSheet::ContactSheet(unsigned numFrames, unsigned columns, int frameWidth, int frameHeight, int tileWidth,
                           const osg::Vec4& background)
    : _numFrames(std::max(numFrames, 1u)), _frameWidth(std::max(frameWidth, 1)),
      _frameHeight(std::max(frameHeight, 1))
{
    _columns = columns > 0 ? columns : static_cast<unsigned>(std::ceil(std::sqrt(double(_numFrames))));
    _columns = std::min(_columns, _numFrames);
    _rows = (_numFrames + _columns - 1) / _columns;
    _tileWidth = std::max(1, std::min(tileWidth, _frameWidth));
    _tileHeight = std::max(1, int(std::lround(double(_frameHeight) * _tileWidth / _frameWidth)));

    const int width = int(_columns) * (_tileWidth + kMargin) + kMargin;
    const int height = int(_rows) * (_tileHeight + kMargin) + kMargin;
    _image = new osg::Image;
    _image->allocateImage(width, height, 1, GL_RGB, GL_UNSIGNED_BYTE);
    unsigned char* data = _image->data();
    for (int i = 0; i < width * height; ++i)
        for (int c = 0; c < 3; ++c)
            data[3 * i + c] = static_cast<unsigned char>(std::lround(std::clamp(background[c], 0.0f, 1.0f) * 255.0f));
}

bool ContactSheet::addFrame(unsigned index, const osg::Image& frame)
{
    if (index >= _numFrames || frame.s() != _frameWidth || frame.t() != _frameHeight ||
        frame.getPixelFormat() != GL_RGB || frame.getDataType() != GL_UNSIGNED_BYTE)
        return false;

    // Tile (column, row) with row 0 at the top; image rows are bottom-first, so the top row of tiles is highest.
    const int column = int(index % _columns);
    const int row = int(index / _columns);
    const int left = kMargin + column * (_tileWidth + kMargin);
    const int bottom = _image->t() - (row + 1) * (_tileHeight + kMargin);

    for (int ty = 0; ty < _tileHeight; ++ty)
    {
        const int y0 = ty * _frameHeight / _tileHeight;
        const int y1 = std::max(y0 + 1, (ty + 1) * _frameHeight / _tileHeight);
        for (int tx = 0; tx < _tileWidth; ++tx)
        {
            const int x0 = tx * _frameWidth / _tileWidth;
            const int x1 = std::max(x0 + 1, (tx + 1) * _frameWidth / _tileWidth);
            unsigned sum[3] = {0, 0, 0};
            for (int y = y0; y < y1; ++y)
            {
                const unsigned char* pixel = frame.data(x0, y);
                for (int x = x0; x < x1; ++x, pixel += 3)
                    for (int c = 0; c < 3; ++c) sum[c] += pixel[c];
            }
            const unsigned count = unsigned((x1 - x0) * (y1 - y0));
            unsigned char* out = _image->data(left + tx, bottom + ty);
            for (int c = 0; c < 3; ++c) out[c] = static_cast<unsigned char>((sum[c] + count / 2) / count);
        }
    }
    _image->dirty();
    return true;
}

} // namespace osgActor
