# The OSG-free part of libosgActor (docs/architecture.md): core (GLM only), the .actor format (io/) and the
# motion-capture parsers (mocap/). Paths are relative to this folder. Included by osgActor/CMakeLists.txt, which
# compiles them into the object library osgActorCore (linked alone into the fuzzers of fuzz/).

set(OSGACTOR_CORE_HEADERS
    core/ActorDefinition
    core/ActorDefinitionBuilder
    core/ActorPose
    core/AlignedAllocator
    core/Clip
    core/ClipBuilder
    core/ClipLibrary
    core/ClipPlayer
    core/Controller
    core/Dof
    core/ForwardKinematicsJob
    core/JointBatches
    core/LocalMatrices
    core/SinCos
    core/Span
    core/Trajectory
    core/WorkerPool)
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
set(OSGACTOR_CORE_SOURCES
    core/ActorDefinition.cpp
    core/ActorDefinitionBuilder.cpp
    core/ActorPose.cpp
    core/Clip.cpp
    core/ClipBuilder.cpp
    core/ClipLibrary.cpp
    core/ClipPlayer.cpp
    core/Controller.cpp
    core/Dof.cpp
    core/ForwardKinematicsJob.cpp
    core/JointBatches.cpp
    core/LocalMatrices.cpp
    core/SinCos.cpp
    core/Trajectory.cpp
    core/WorkerPool.cpp
    core/ik/CcdIkJob.cpp
    core/ik/DlsIkJob.cpp
    core/ik/IkChain.cpp
    core/ik/IkController.cpp
    core/ik/IkJob.cpp
    core/ik/IkKinematics.cpp
    core/ik/IkSolve.cpp
    core/ik/SweepAcceleration.cpp
    core/ik/TwoBoneClosedForm.cpp
    core/ik/TwoBoneIkJob.cpp)

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
    io/DocumentDifference)
set(OSGACTOR_IO_SOURCES
    io/ActorDocument.cpp
    io/ActorLexer.cpp
    io/ActorReader.cpp
    io/ActorSyntax.cpp
    io/ActorWriter.cpp
    io/AngleAxis.cpp
    io/DocumentDifference.cpp
    io/PlayerDocument.cpp)

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
