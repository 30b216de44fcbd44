// IK chains in .actor files: the "ikchain" section read, checked against the skeleton with file:line errors,
// written back, and carried by ActorNode through ActorSceneIO.
#include <osgActor/ActorSceneIO>
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>

#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <sstream>

using namespace osgActor;

namespace {

const char* const kLegActor = R"(osgactor 1
actor legged {
    joint hip {
        dof rx min -120 max 45; dof ry min -45 max 45; dof rz min -45 max 45
        joint knee {
            offset 0 0 -0.45
            dof rx min 0 max 150
            joint ankle {
                offset 0 0 -0.42
                dof rx; dof ry; dof rz
                joint toe { offset 0 0.12 -0.05 }
            }
        }
    }
)";

ActorReadResult read(const std::string& text)
{
    std::istringstream in(text);
    return readActor(in, "t.actor");
}

/** Reads a leg actor with the given chain sections, which must fail; nothing half-built may come back. */
std::string chainError(const std::string& sections)
{
    const ActorReadResult result = read(std::string(kLegActor) + sections + "}\n");
    EXPECT_FALSE(result) << sections;
    EXPECT_EQ(result.definition, nullptr);
    EXPECT_TRUE(result.ikChains.empty());
    EXPECT_TRUE(result.document.ikChains.empty());
    return result.error;
}

std::string written(const ActorDocument& document)
{
    std::ostringstream out;
    writeActor(out, document);
    return out.str();
}

} // namespace

TEST(IkChainFormat, RefusesBadSectionsWithFileAndLine)
{
    // The sections start on line 15.
    EXPECT_EQ(chainError("    ikchain leg\n"), "t.actor:15: 'ikchain' needs a block in braces");
    EXPECT_EQ(chainError("    ikchain { root hip }\n"), "t.actor:15: 'ikchain' takes 1 value, not 0");
    EXPECT_EQ(chainError("    ikchain leg { effector ankle }\n"), "t.actor:15: IK chain 'leg' has no 'root'");
    EXPECT_EQ(chainError("    ikchain leg { root hip }\n"), "t.actor:15: IK chain 'leg' has no 'effector'");
    EXPECT_EQ(chainError("    ikchain leg {\n root hip\n effector ankle\n bend knee\n }\n"),
              "t.actor:18: unknown keyword 'bend' in an ikchain");
    EXPECT_EQ(chainError("    ikchain leg { root hip; effector ankle; solver fabrik }\n"),
              "t.actor:15: unknown IK solver 'fabrik' (twobone, ccd or dls)");
    EXPECT_EQ(chainError("    ikchain leg { root hip; effector ankle; iterations 0 }\n"),
              "t.actor:15: 'iterations' must be a whole number from 1 to 1000000");
    EXPECT_EQ(chainError("    ikchain leg { root hip; effector ankle; iterations 2.5 }\n"),
              "t.actor:15: 'iterations' must be a whole number from 1 to 1000000");
    EXPECT_EQ(chainError("    ikchain leg { root hip; effector ankle; tolerance 0 }\n"),
              "t.actor:15: 'tolerance' must be between 0 and 1 (a fraction of the chain's length)");
    EXPECT_EQ(chainError("    ikchain leg { root hip; effector ankle; tolerance nan }\n"),
              "t.actor:15: 'nan' is not a finite number");
    EXPECT_EQ(chainError("    ikchain leg { root hip; effector ankle; joint_weight knee -1 }\n"),
              "t.actor:15: 'joint_weight' must not be negative");
    EXPECT_EQ(chainError("    ikchain leg { root hip; effector ankle; dof_weight knee.rx }\n"),
              "t.actor:15: 'dof_weight' takes 2 values, not 1");
    // Found by the fuzzer: a weight without any argument read its name from an empty list.
    EXPECT_EQ(chainError("    ikchain leg { root hip; effector ankle; dof_weight }\n"),
              "t.actor:15: 'dof_weight' takes 2 values, not 0");
    EXPECT_EQ(chainError("    ikchain leg { root hip; effector ankle; joint_weight }\n"),
              "t.actor:15: 'joint_weight' takes 2 values, not 0");
    EXPECT_EQ(chainError("    ikchain leg { root hip; root knee; effector ankle }\n"),
              "t.actor:15: 'root' is given twice");
    EXPECT_EQ(chainError("    ikchain leg { root hip; effector ankle }\n    ikchain leg { root knee; effector toe }\n"),
              "t.actor:16: IK chain 'leg' is given twice (first at line 15)");
}

TEST(IkChainFormat, ChecksChainsAgainstTheSkeleton)
{
    EXPECT_EQ(chainError("    ikchain leg { root thigh; effector ankle }\n"),
              "t.actor:15: IK chain 'leg' of actor 'legged': no root joint named 'thigh'");
    EXPECT_EQ(chainError("    ikchain leg { root ankle; effector hip }\n"),
              "t.actor:15: IK chain 'leg' of actor 'legged': effector 'hip' is not below root 'ankle'");
    EXPECT_EQ(chainError("    ikchain leg { root hip; effector ankle }\n\n"
                         "    ikchain foot { root ankle; effector ankle }\n"),
              "t.actor:17: IK chain 'foot' of actor 'legged': effector 'ankle' is not below root 'ankle' (a chain "
              "needs at least one bone)");
    const std::string twoBone = chainError("    ikchain leg { root hip; effector toe; solver twobone }\n");
    EXPECT_EQ(twoBone.rfind("t.actor:15: IK chain 'leg' of actor 'legged': the two-bone solver needs", 0), 0u)
        << twoBone;
    EXPECT_EQ(chainError("    ikchain leg { root hip; effector ankle; dof_weight hip.tx 1 }\n"),
              "t.actor:15: IK chain 'leg' of actor 'legged': DOF weight names 'hip.tx', not a DOF of the chain");
}

TEST(IkChainFormat, ReadsWritesAndReadsBackTheSameChains)
{
    const std::string text = std::string(kLegActor) + R"(    ikchain left_leg {
        root hip
        effector ankle
        effector_offset 0 0.12 -0.05
        solver twobone
        iterations 4
        tolerance 1e-05
        joint_weight ankle 0.5
        dof_weight hip.rz 0
    }
    ikchain "whole leg" { root hip; effector toe; solver dls }
}
)";
    const ActorReadResult result = read(text);
    ASSERT_TRUE(result) << result.error;
    ASSERT_EQ(result.ikChains.size(), 2u);
    const IkChainSpec& leg = result.ikChains[0]->getSpec();
    EXPECT_EQ(leg.name, "left_leg");
    EXPECT_EQ(leg.rootJoint, "hip");
    EXPECT_EQ(leg.effectorJoint, "ankle");
    EXPECT_EQ(leg.effectorOffset, glm::dvec3(0, 0.12, -0.05));
    EXPECT_EQ(leg.solver, IkSolverType::TwoBone);
    EXPECT_EQ(leg.maxIterations, 4u);
    EXPECT_EQ(leg.tolerance, 1e-5);
    ASSERT_EQ(leg.jointWeights.size(), 1u);
    EXPECT_EQ(leg.jointWeights[0].name, "ankle");
    EXPECT_EQ(leg.jointWeights[0].weight, 0.5);
    ASSERT_EQ(leg.dofWeights.size(), 1u);
    EXPECT_EQ(leg.dofWeights[0].name, "hip.rz");
    EXPECT_EQ(leg.dofWeights[0].weight, 0.0);
    EXPECT_EQ(result.ikChains[0]->getNumDofs(), 6u) << "hip.rz frozen by its weight";
    const IkChainSpec& whole = result.ikChains[1]->getSpec();
    EXPECT_EQ(whole.name, "whole leg");
    EXPECT_EQ(whole.solver, IkSolverType::Dls);
    EXPECT_EQ(whole.maxIterations, kDefaultIkIterations);
    EXPECT_EQ(whole.tolerance, kDefaultIkTolerance);

    // Written back: only what differs from the defaults, and a fixed point.
    const std::string first = written(result.document);
    EXPECT_NE(first.find("    ikchain \"whole leg\" {\n        root hip\n        effector toe\n"
                         "        solver dls\n    }\n"),
              std::string::npos) << first;
    const ActorReadResult again = read(first);
    ASSERT_TRUE(again) << again.error;
    ASSERT_EQ(again.ikChains.size(), 2u);
    const IkChainSpec& legAgain = again.ikChains[0]->getSpec();
    EXPECT_EQ(legAgain.effectorOffset, leg.effectorOffset);
    EXPECT_EQ(legAgain.maxIterations, leg.maxIterations);
    EXPECT_EQ(legAgain.tolerance, leg.tolerance);
    EXPECT_EQ(legAgain.dofWeights[0].name, "hip.rz");
    EXPECT_EQ(again.ikChains[1]->getName(), "whole leg");
    EXPECT_EQ(written(again.document), first);
}

TEST(IkChainFormat, ActorsCarryTheirChainsThroughSceneIO)
{
    const ActorReadResult result =
        read(std::string(kLegActor) + "    ikchain leg { root hip; effector ankle; solver twobone }\n}\n");
    ASSERT_TRUE(result) << result.error;
    const ActorNodeResult made = createActorNode(result.document, result.definition, "t.actor", nullptr);
    ASSERT_TRUE(made.actor.valid()) << made.error;
    ASSERT_EQ(made.actor->getIkChains().size(), 1u);
    const IkChainPtr leg = made.actor->findIkChain("leg");
    ASSERT_TRUE(leg);
    EXPECT_EQ(leg->getSolver(), IkSolverType::TwoBone);
    EXPECT_EQ(made.actor->findIkChain("arm"), nullptr);

    // Copies share the immutable chains; the actor refuses chains it cannot carry.
    osg::ref_ptr<ActorNode> copy = osg::clone(made.actor.get(), osg::CopyOp::SHALLOW_COPY);
    EXPECT_EQ(copy->findIkChain("leg"), leg);
    EXPECT_FALSE(copy->addIkChain(leg)) << "the name is taken";
    EXPECT_FALSE(copy->addIkChain(IkChainPtr()));
    const ActorReadResult other = read("osgactor 1\nactor other {\n joint a\n"
                                       " joint b { parent a; offset 1 0 0; dof rz }\n"
                                       " ikchain leg2 { root a; effector b }\n}\n");
    ASSERT_TRUE(other) << other.error;
    EXPECT_FALSE(copy->addIkChain(other.ikChains[0])) << "built for another skeleton";
    EXPECT_TRUE(copy->removeIkChain("leg"));
    EXPECT_TRUE(copy->getIkChains().empty());
    EXPECT_EQ(made.actor->getIkChains().size(), 1u) << "the original keeps its own list";

    // Written back from the actor.
    const ActorDocument document = extractActorDocument(*made.actor);
    ASSERT_EQ(document.ikChains.size(), 1u);
    EXPECT_EQ(document.ikChains[0].spec.name, "leg");
    EXPECT_NE(written(document).find("ikchain leg {"), std::string::npos);

    // A chain the skeleton cannot carry: no actor, and the error names the line.
    ActorDocument broken = result.document;
    broken.ikChains[0].spec.effectorJoint = "wing";
    broken.ikChains[0].line = 15;
    const ActorNodeResult refused = createActorNode(broken, result.definition, "t.actor", nullptr);
    EXPECT_FALSE(refused.actor.valid());
    EXPECT_EQ(refused.error, "t.actor:15: IK chain 'leg' of actor 'legged': no effector joint named 'wing'");
}

TEST(IkChainFormat, ChainsSurviveEveryFormatThroughOsgDB)
{
    const ActorReadResult result =
        read(std::string(kLegActor) +
             "    ikchain leg { root hip; effector ankle; solver twobone; iterations 3 }\n}\n");
    ASSERT_TRUE(result) << result.error;
    const ActorNodeResult made = createActorNode(result.document, result.definition, "t.actor", nullptr);
    ASSERT_TRUE(made.actor.valid()) << made.error;
    for (const char* extension : {"actor", "osgt", "osgb", "osg"})
    {
        const std::string file = std::string(OSGACTOR_TEST_BINARY_DIR) + "/ik_chains." + extension;
        ASSERT_TRUE(osgDB::writeNodeFile(*made.actor, file)) << file;
        osg::ref_ptr<osg::Node> node = osgDB::readNodeFile(file);
        ActorNode* actor = dynamic_cast<ActorNode*>(node.get());
        if (!actor && node.valid())
            if (osg::Group* group = node->asGroup())
                if (group->getNumChildren() == 1) actor = dynamic_cast<ActorNode*>(group->getChild(0));
        ASSERT_NE(actor, nullptr) << file;
        ASSERT_EQ(actor->getIkChains().size(), 1u) << file;
        EXPECT_EQ(actor->getIkChains()[0]->getName(), "leg") << file;
        EXPECT_EQ(actor->getIkChains()[0]->getSolver(), IkSolverType::TwoBone) << file;
        EXPECT_EQ(actor->getIkChains()[0]->getMaxIterations(), 3u) << file;
    }
}
