#include <osgActor/mocap/AmcReader>
#include <osgActor/mocap/BvhReader>
#include <osgActor/mocap/MotionFile>

namespace osgActor {

MocapImport readMotionFile(const std::string& path, const MotionFileOptions& options)
{
    const std::string extension = lowerExtensionOf(path);
    if (extension == ".bvh")
    {
        BvhImportOptions bvh;
        bvh.name = options.name;
        bvh.scale = options.scale;
        bvh.fileUpAxis = options.fileUpAxis;
        bvh.dropFirstFrame = options.dropFirstFrame;
        bvh.absoluteRootPosition = options.absoluteRootPosition;
        return readBvhFile(path, bvh);
    }
    MocapImport failed;
    if (extension != ".amc")
    {
        failed.error = path + ": not a motion file (expected .bvh, or .amc with its ASF skeleton)";
        return failed;
    }
    if (options.skeletonFile.empty())
    {
        failed.error = path + ": an AMC motion needs the ASF skeleton it was captured on";
        return failed;
    }
    AsfImportOptions asf;
    asf.scale = options.scale;
    asf.fileUpAxis = options.fileUpAxis;
    asf.frameRate = options.amcFrameRate;
    asf.applyLimits = options.applyAsfLimits;
    const AsfImport skeleton = readAsfFile(options.skeletonFile, asf);
    if (!skeleton)
    {
        failed.error = skeleton.error;
        return failed;
    }
    MocapImport motion = readAmcFile(path, skeleton, options.name);
    motion.warnings.insert(motion.warnings.begin(), skeleton.warnings.begin(), skeleton.warnings.end());
    return motion;
}

} // namespace osgActor
