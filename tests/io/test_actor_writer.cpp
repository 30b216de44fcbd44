#include <osgActor/io/ActorReader>
#include <osgActor/core/ClipBuilder>
#include <osgActor/io/ActorWriter>

#include <glm/ext/quaternion_trigonometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

using namespace osgActor;

namespace {

const double kDegree = 3.14159265358979323846 / 180.0;

std::string written(const ActorDocument& document)
{
    std::ostringstream out;
    writeActor(out, document);
    return out.str();
}

ActorReadResult readText(const std::string& text)
{
    std::istringstream in(text);
    return readActor(in, "w.actor");
}

/** An actor with every feature the format has, built through the API (radians). */
ActorDocument makeRichDocument()
{
    ActorDefinitionBuilder b("rich \"one\"");
    b.addJoint("root").offset(0.1 + 0.2, -1.0 / 3.0, 2.0).dofs(kTranslationDofs | Dof::RZ)
        .translationMode(TranslationMode::BeforeRotation).eulerOrder(EulerOrder::ZXY);
    b.addJoint("left arm", "root").offset(0, 0.2, 0).rotation(0.7, 0.3, -0.5, 0.8).dofs(kPaperDofs)
        .limits(Dof::RX, -1.2, 2.1).defaultValue(Dof::RX, 0.3).weight(Dof::RY, 0.25).limits(Dof::TX, 0.0, 0.4);
    b.addJoint("hand", "left arm").offset(0.3, 0, 0);
    b.addJoint("right arm", "root").offset(0, -0.2, 0).rotation(3.14159265358979323846, 1, 0, 0)
        .dofs(dofBit(Dof::RY));
    const BuildResult built = b.build();
    EXPECT_TRUE(built) << built.error;
    ActorDocument document = makeDocument(*built.definition);
    document.preTranslation = glm::dvec3(5, 0, 0);
    document.preRotation = glm::angleAxis(0.4, glm::dvec3(0, 0, 1));
    document.postTranslation = glm::dvec3(0, 0, 0.9);
    document.blocked = true;
    document.boundsCoverRotations = false; // not the default, so it is written
    document.joints[1].values[0] = 1.0;
    document.joints[1].hidden = true;
    GeometryDescription cone;
    cone.kind = GeometryKind::Cone;
    cone.radius = 0.05;
    cone.height = 0.3;
    cone.position = glm::dvec3(0.15, 0, 0);
    cone.rotation = glm::angleAxis(glm::radians(90.0), glm::dvec3(0, 1, 0));
    cone.color = glm::dvec4(0.2, 0.4, 0.6, 1.0);
    document.joints[1].geometry.push_back(cone);
    GeometryDescription model;
    model.kind = GeometryKind::Model;
    model.file = "tools/spanner.osgt";
    model.scale = 0.5;
    document.joints[2].geometry.push_back(model);
    IkChainSpec arm;
    arm.name = "arm";
    arm.rootJoint = "left arm";
    arm.effectorJoint = "hand";
    document.ikChains.push_back(IkChainDocument{arm, 0});
    ClipBuilder keyed("wave");
    const unsigned rx = keyed.addChannel("left arm.rx", Interpolation::Cubic);
    keyed.addKey(rx, 0.0, 0.1);
    keyed.addKey(rx, 0.4, 1.0 / 3.0);
    const unsigned tx = keyed.addChannel("root.tx", Interpolation::Step);
    keyed.addKey(tx, 0.2, 0.05);
    ClipBuilder uniform("shuffle");
    uniform.addChannel("root.rz");
    uniform.addChannel("root.ty");
    uniform.setFrames(30.0, {0.0, 0.0, 0.01, 0.002, 0.02, 0.004});
    for (ClipBuilder* builder : {&keyed, &uniform})
    {
        const ClipBuildResult clip = builder->build();
        EXPECT_TRUE(clip) << clip.error;
        ClipDocument clipDocument;
        clipDocument.clip = clip.clip;
        document.clips.push_back(clipDocument);
    }
    return document;
}

void expectSameDefinition(const ActorDefinition& a, const ActorDefinition& b)
{
    EXPECT_EQ(a.getName(), b.getName());
    ASSERT_EQ(a.getNumJoints(), b.getNumJoints());
    ASSERT_EQ(a.getNumDofs(), b.getNumDofs());
    for (unsigned j = 0; j < a.getNumJoints(); ++j)
    {
        EXPECT_EQ(a.getJointName(j), b.getJointName(j));
        EXPECT_EQ(a.getParent(j), b.getParent(j));
        EXPECT_EQ(a.getEulerOrder(j), b.getEulerOrder(j));
        EXPECT_EQ(a.getTranslationMode(j), b.getTranslationMode(j));
        EXPECT_EQ(a.getDofMask(j), b.getDofMask(j));
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(a.getOffsetTranslation(j)[c], b.getOffsetTranslation(j)[c], 1e-11);
        // The same rotation: q and -q are equal.
        const double dot = glm::dot(a.getOffsetRotation(j), b.getOffsetRotation(j));
        EXPECT_NEAR(std::abs(dot), 1.0, 1e-11) << a.getJointName(j);
    }
    for (unsigned d = 0; d < a.getNumDofs(); ++d)
    {
        EXPECT_EQ(std::isinf(a.getDofMin(d)), std::isinf(b.getDofMin(d)));
        if (!std::isinf(a.getDofMin(d))) { EXPECT_NEAR(a.getDofMin(d), b.getDofMin(d), 1e-11); }
        if (!std::isinf(a.getDofMax(d))) { EXPECT_NEAR(a.getDofMax(d), b.getDofMax(d), 1e-11); }
        EXPECT_NEAR(a.getDofDefault(d), b.getDofDefault(d), 1e-11);
        EXPECT_EQ(a.getDofWeight(d), b.getDofWeight(d));
    }
}

} // namespace

TEST(ActorWriter, WritesOnlyWhatDiffersFromTheDefaultsInDegrees)
{
    ActorDefinitionBuilder b("arm");
    b.addJoint("shoulder").offset(0, 0, 1.5).dofs(kRotationDofs);
    b.addJoint("elbow", "shoulder").offset(0, 0, -0.3).dofs(dofBit(Dof::RX)).limits(Dof::RX, 0.0, 150 * kDegree)
        .rotation(90 * kDegree, 0, 0, 1);
    ActorDocument document = makeDocument(*b.build().definition);
    document.joints[1].values[0] = 45 * kDegree;
    GeometryDescription box;
    box.size = glm::dvec3(0.1, 0.1, 0.3);
    box.position = glm::dvec3(0, 0, -0.15);
    box.color = glm::dvec4(0.8, 0.6, 0.4, 1.0);
    document.joints[1].geometry.push_back(box);
    EXPECT_EQ(written(document),
              R"(# An osgActor actor (docs/actor-format.md): angles in degrees, lengths in model units.
osgactor 1
actor arm {
    joint shoulder {
        offset 0 0 1.5
        dof rx
        dof ry
        dof rz
        joint elbow {
            offset 0 0 -0.3
            rotation 90 0 0 1
            dof rx min 0 max 150 value 45
            shape box {
                size 0.1 0.1 0.3
                position 0 0 -0.15
                color 0.8 0.6 0.4
            }
        }
    }
}
)");
}

TEST(ActorWriter, ReadingWhatItWroteGivesTheSameActorAndWritingAgainTheSameBytes)
{
    const ActorDocument original = makeRichDocument();
    const std::string first = written(original);
    const ActorReadResult read = readText(first);
    ASSERT_TRUE(read) << read.error << "\n" << first;
    const BuildResult built = buildDefinition(original, "original");
    ASSERT_TRUE(built) << built.error;
    expectSameDefinition(*built.definition, *read.definition);

    const ActorDocument& again = read.document;
    EXPECT_NEAR(again.preRotation.z, original.preRotation.z, 1e-12);
    EXPECT_EQ(again.postTranslation, original.postTranslation);
    EXPECT_TRUE(again.blocked);
    EXPECT_FALSE(again.boundsCoverRotations);
    ASSERT_TRUE(again.joints[1].values[0].has_value());
    EXPECT_NEAR(*again.joints[1].values[0], 1.0, 1e-11);
    EXPECT_TRUE(again.joints[1].hidden);
    ASSERT_EQ(again.joints[1].geometry.size(), 1u);
    EXPECT_EQ(again.joints[1].geometry[0].kind, GeometryKind::Cone);
    EXPECT_NEAR(again.joints[1].geometry[0].rotation.y, original.joints[1].geometry[0].rotation.y, 1e-12);
    ASSERT_EQ(again.joints[2].geometry.size(), 1u);
    EXPECT_EQ(again.joints[2].geometry[0].file, "tools/spanner.osgt");
    EXPECT_TRUE(again.sections.empty());
    ASSERT_EQ(again.ikChains.size(), 1u);
    EXPECT_EQ(again.ikChains[0].spec.rootJoint, "left arm");
    ASSERT_EQ(again.clips.size(), 2u);
    const Clip& wave = *again.clips[0].clip;
    EXPECT_EQ(wave.getChannel(0).interpolation, Interpolation::Cubic);
    EXPECT_NEAR(wave.getKeyValue(0, 1), 1.0 / 3.0, 1e-12);
    EXPECT_EQ(wave.getKeyTime(1, 0), 0.2);
    const Clip& shuffle = *again.clips[1].clip;
    ASSERT_TRUE(shuffle.isUniform());
    EXPECT_EQ(shuffle.getNumFrames(), 3u);
    EXPECT_NEAR(shuffle.getFrame(2)[0], 0.02, 1e-13) << "12 digits of degrees";
    EXPECT_EQ(shuffle.getFrame(2)[1], 0.004);

    EXPECT_EQ(written(again), first);
}

TEST(ActorWriter, NestsChildrenAndWritesOrphansWithTheirParent)
{
    ActorDocument document;
    document.name = "flat";
    JointDocument a, b, c;
    a.spec.name = "a";
    b.spec.name = "b";
    b.spec.parent = "missing";
    c.spec.name = "c";
    c.spec.parent = "a";
    document.joints = {c, b, a};
    EXPECT_EQ(written(document), "# An osgActor actor (docs/actor-format.md): angles in degrees, lengths in model "
                                 "units.\nosgactor 1\nactor flat {\n    joint a {\n        joint c\n    }\n"
                                 "    joint b {\n        parent missing\n    }\n}\n");
}
