// render_two_boxes <scene> <reference pattern>: renders a plain OSG scene at 0, 0.5, 1 and 1.5 s through
// osgActor::Offscreen and holds each frame against its reference, byte for byte, as a user's own test program
// would. Exit status 0 when all four match.
#include <osgActor/Offscreen/ImageComparison>
#include <osgActor/Offscreen/OffscreenRenderer>
#include <osgActor/Offscreen/RenderFrames>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv)
{
    if (argc != 3)
    {
        std::cerr << "usage: render_two_boxes <scene> <reference pattern, %04d the frame>" << std::endl;
        return 2;
    }
    std::string error;
    if (!osgActor::OffscreenRenderer::glResolvesToOsMesa(error))
    {
        std::cerr << error << std::endl;
        return 1;
    }

    osgActor::RenderSettings settings;
    settings.width = 160;
    settings.height = 120;
    settings.fps = 2.0;
    settings.hasEye = true;
    settings.eye = osg::Vec3d(0.0, -6.0, 2.5);
    settings.hasCenter = true;
    settings.center = osg::Vec3d(0.0, 0.0, 0.0);
    std::vector<osg::ref_ptr<osg::Image>> images;
    if (!osgActor::renderFile(argv[1], {0.0, 0.5, 1.0, 1.5}, settings, images, error))
    {
        std::cerr << error << std::endl;
        return 1;
    }

    int status = 0;
    for (unsigned frame = 0; frame < images.size(); ++frame)
    {
        char file[1024];
        std::snprintf(file, sizeof file, argv[2], frame);
        const osg::ref_ptr<osg::Image> reference = osgActor::readRgbImage(file, error);
        if (!reference)
        {
            std::cerr << error << std::endl;
            return 1;
        }
        const osgActor::ImageComparison comparison = osgActor::compareImages(*images[frame], *reference, 0);
        std::cout << "frame " << frame << ": largest difference " << comparison.maxChannelDifference << ", PSNR "
                  << comparison.psnr << " dB" << std::endl;
        if (!comparison.matches()) status = 1;
    }
    // The scene moves: the first and last frames differ, so matching all four means something.
    if (osgActor::compareImages(*images.front(), *images.back(), 0).matches())
    {
        std::cerr << "the first and last frames are the same: the scene did not move" << std::endl;
        status = 1;
    }
    return status;
}
