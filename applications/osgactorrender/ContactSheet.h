/* osgactorrender: many frames in one image. */
#ifndef OSGACTORRENDER_CONTACTSHEET_H
#define OSGACTORRENDER_CONTACTSHEET_H 1

#include <osg/Image>
#include <osg/Vec4>

namespace osgActorRender {

/** A grid of reduced frames, first frame top left, filled row by row, with a margin between tiles. Frames are added
  * one at a time and reduced at once (an average over each tile pixel's footprint), so a long batch never keeps
  * its full-size frames in memory. */
class ContactSheet
{
public:
    /** numFrames tiles of at most tileWidth pixels across (frames are only ever reduced), in columns columns (0:
      * as square a grid as possible), for frames of frameWidth x frameHeight. */
    ContactSheet(unsigned numFrames, unsigned columns, int frameWidth, int frameHeight, int tileWidth,
                 const osg::Vec4& background);

    /** Reduces an RGB frame of the size given at construction into tile number index; false (and nothing drawn)
      * if the index or the image does not fit. */
    bool addFrame(unsigned index, const osg::Image& frame);

    const osg::Image* getImage() const { return _image.get(); }
    unsigned getColumns() const { return _columns; }
    unsigned getRows() const { return _rows; }
    int getTileWidth() const { return _tileWidth; }
    int getTileHeight() const { return _tileHeight; }

    static const int kMargin = 4; // pixels around and between tiles

private:
    unsigned _numFrames;
    unsigned _columns;
    unsigned _rows;
    int _frameWidth;
    int _frameHeight;
    int _tileWidth;
    int _tileHeight;
    osg::ref_ptr<osg::Image> _image;
};

} // namespace osgActorRender

#endif
