# The OSG-free part of libosgActor (docs/architecture.md): core (GLM only), the .actor format (io/) and the
# motion-capture parsers (mocap/). Paths are relative to this folder. Included by osgActor/CMakeLists.txt, which
# compiles them into the object library osgActorCore (linked alone into the fuzzers of fuzz/).

# core/: the concepts a user reads first and the per-frame jobs, installed as the API.
set(OSGACTOR_CORE_HEADERS
    core/ActorDefinition
    core/ActorDefinitionBuilder
    core/ActorPose
    core/ActorTransforms
    core/Clip
    core/ClipBuilder
    core/ClipLibrary
    core/ClipPlayer
    core/Controller
    core/Dof
    core/LocalMatricesJob
    core/LocalToModelJob
    core/PlayHead
    core/SamplingJob
    core/Span
    core/Trajectory)
# core/detail/: machinery of the per-frame path, not API. These few are installed only because public headers hold
# them as members; the rest are not installed at all.
set(OSGACTOR_CORE_DETAIL_HEADERS
    core/detail/AlignedAllocator
    core/detail/JointBatches
    core/detail/LocalMatrices
    core/detail/NameIndex)
set(OSGACTOR_CORE_PRIVATE_HEADERS
    core/detail/AffineColumns.h
    core/detail/ByteFlags.h
    core/detail/Column.h
    core/detail/HotPath.h
    core/detail/JointChildren.h
    core/detail/JointMatrixKernel.h
    core/detail/SinCos
    core/detail/SinCosColumn.h
    core/detail/WorkerPool)
set(OSGACTOR_CORE_IK_HEADERS
    core/ik/Arctangent
    core/ik/CcdIkJob
    core/ik/DlsIkJob
    core/ik/IkChain
    core/ik/IkController
    core/ik/IkGoal
    core/ik/IkJob
    core/ik/IkKinematics
    core/ik/IkSolve
    core/ik/SweepAcceleration
    core/ik/TwoBoneClosedForm
    core/ik/TwoBoneIkJob)
set(OSGACTOR_CORE_RETARGET_HEADERS
    core/retarget/BuiltInJointMaps
    core/retarget/ClipFrames
    core/retarget/FootContacts
    core/retarget/HAnimHumanoid
    core/retarget/JointMap
    core/retarget/JointMapGuess
    core/retarget/JointRotationFit
    core/retarget/RetargetClip
    core/retarget/RetargetIkJob
    core/retarget/RetargetJob
    core/retarget/RetargetLimbs
    core/retarget/RetargetMeasures
    core/retarget/RetargetRig)
set(OSGACTOR_CORE_SOURCES
    core/ActorDefinition.cpp
    core/ActorDefinitionBuilder.cpp
    core/ActorPose.cpp
    core/ActorTransforms.cpp
    core/Clip.cpp
    core/ClipBuilder.cpp
    core/ClipLibrary.cpp
    core/ClipPlayer.cpp
    core/Controller.cpp
    core/Dof.cpp
    core/LocalMatricesJob.cpp
    core/LocalToModelJob.cpp
    core/PlayHead.cpp
    core/SamplingJob.cpp
    core/Trajectory.cpp
    core/detail/JointBatches.cpp
    core/detail/NameIndex.cpp
    core/detail/JointChildren.cpp
    core/detail/LocalMatrices.cpp
    core/detail/SinCos.cpp
    core/detail/WorkerPool.cpp
    core/ik/CcdIkJob.cpp
    core/ik/DlsIkJob.cpp
    core/ik/IkChain.cpp
    core/ik/IkController.cpp
    core/ik/IkJob.cpp
    core/ik/IkKinematics.cpp
    core/ik/IkSolve.cpp
    core/ik/SweepAcceleration.cpp
    core/ik/TwoBoneClosedForm.cpp
    core/ik/TwoBoneIkJob.cpp
    core/retarget/BuiltInJointMaps.cpp
    core/retarget/ClipFrames.cpp
    core/retarget/FootContacts.cpp
    core/retarget/HAnimHumanoid.cpp
    core/retarget/JointMap.cpp
    core/retarget/JointMapGuess.cpp
    core/retarget/JointRotationFit.cpp
    core/retarget/RetargetClip.cpp
    core/retarget/RetargetIkJob.cpp
    core/retarget/RetargetJob.cpp
    core/retarget/RetargetLimbs.cpp
    core/retarget/RetargetMeasures.cpp
    core/retarget/RetargetRig.cpp)

# Skinned meshes (core/skin): the skin data, its builder and binding, and the per-frame jobs (skinning matrices,
# CPU skinning, bounds).
set(OSGACTOR_CORE_SKIN_HEADERS
    core/skin/Skin
    core/skin/SkinBinding
    core/skin/SkinBoundBoxes
    core/skin/SkinBoundsJob
    core/skin/SkinBuilder
    core/skin/SkinningJob
    core/skin/SkinningMatricesJob)
set(OSGACTOR_CORE_SKIN_SOURCES
    core/skin/Skin.cpp
    core/skin/SkinBinding.cpp
    core/skin/SkinBoundBoxes.cpp
    core/skin/SkinBoundsJob.cpp
    core/skin/SkinBuilder.cpp
    core/skin/SkinningJob.cpp
    core/skin/SkinningMatricesJob.cpp)

# How every text format reads and writes numbers and splits lines and words: plain C++, used by io/ and mocap/
# (which include neither each other's parsers nor OSG for it).
set(OSGACTOR_TEXT_HEADERS
    text/Degrees
    text/Numbers
    text/TextLines)
set(OSGACTOR_TEXT_SOURCES
    text/Degrees.cpp
    text/Numbers.cpp
    text/TextLines.cpp)

# The .actor file format: document model, lexer, syntax, reader, writer. Plain C++ on GLM like the core (no OSG, no
# osgDB), so it is compiled with it.
set(OSGACTOR_IO_HEADERS
    io/ActorDocument
    io/ActorLexer
    io/ActorReader
    io/ActorSyntax
    io/ActorWriter
    io/AngleAxis
    io/ClipRetarget
    io/DocumentDifference
    io/JointMapSection
    io/SyntaxWriter)
set(OSGACTOR_IO_SOURCES
    io/ActorDocument.cpp
    io/ActorLexer.cpp
    io/ActorReader.cpp
    io/ActorSyntax.cpp
    io/ActorWriter.cpp
    io/AngleAxis.cpp
    io/ClipRetarget.cpp
    io/DocumentDifference.cpp
    io/JointMapSection.cpp
    io/PlayerDocument.cpp
    io/SyntaxWriter.cpp)

# Motion-capture parsers: plain C++ on std::istream, GLM only like the core (built into the same object library).
set(OSGACTOR_MOCAP_HEADERS
    mocap/AmcReader
    mocap/AsfReader
    mocap/BvhReader
    mocap/BvhWriter
    mocap/MocapImport
    mocap/MotionFile
    mocap/PositionsCsv
    mocap/TrajectoryCsv)
set(OSGACTOR_MOCAP_SOURCES
    mocap/AmcReader.cpp
    mocap/AsfReader.cpp
    mocap/BvhReader.cpp
    mocap/BvhWriter.cpp
    mocap/MocapImport.cpp
    mocap/MotionFile.cpp
    mocap/PositionsCsv.cpp
    mocap/TrajectoryCsv.cpp)
