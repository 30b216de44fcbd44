#include "SoakIk"

#include <osgActor/GlmOsg>
#include <osgActor/core/ActorDefinitionBuilder>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace osgActor {
namespace test {

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
/** Most goal nodes in the scene, and out of it but alive, at any time. */
const unsigned kMaxGoalNodes = 12;
const unsigned kMaxDetached = 4;

/** A limb or longer chain of data/humanoid.actor. */
struct ChainPlace
{
    const char* name;
    const char* root;
    const char* effector;
    glm::dvec3 offset;
    bool twoBone; // a limb the analytic solver takes
    const char* frozenDof; // given weight 0 in some of the chains (nullptr: none)
};

const ChainPlace kPlaces[] = {
    {"l_leg", "l_hip", "l_ankle", {0.0, -0.04, -0.07}, true, "l_hip.ry"},
    {"r_leg", "r_hip", "r_ankle", {0.0, 0.0, 0.0}, true, nullptr},
    {"l_arm", "l_shoulder", "l_wrist", {0.0, 0.0, -0.14}, true, "l_shoulder.rz"},
    {"r_arm", "r_shoulder", "r_wrist", {0.0, 0.0, 0.0}, true, nullptr},
    {"l_foot", "l_hip", "l_midtarsal", {0.0, -0.08, 0.0}, false, "l_ankle.rz"},
    {"head", "vl5", "skullbase", {0.0, 0.0, 0.1}, false, nullptr},
    // From the pelvis, whose translations have no limits: a goal out of reach can drag the whole body.
    {"body", "HumanoidRoot", "r_wrist", {0.0, 0.0, -0.1}, false, "HumanoidRoot.rz"},
};

IkChainPtr buildChain(const ActorDefinition& definition, const IkChainSpec& spec)
{
    const IkChainBuildResult built = buildIkChain(definition, spec);
    if (!built) throw std::runtime_error("soak chain " + spec.name + ": " + built.error);
    return built.chain;
}

/** Three joints in a row, for a chain that fits no humanoid. */
IkChainPtr makeForeignChain()
{
    ActorDefinitionBuilder builder("stick");
    builder.addJoint("a").dofs(kRotationDofs);
    builder.addJoint("b", "a").offset(0, 0, 1).dofs(dofBit(Dof::RX));
    builder.addJoint("c", "b").offset(0, 0, 1);
    const BuildResult result = builder.build();
    if (!result) throw std::runtime_error(result.error);
    IkChainSpec spec;
    spec.name = "stick";
    spec.rootJoint = "a";
    spec.effectorJoint = "c";
    return buildChain(*result.definition, spec);
}

bool isFinite(const osg::Vec3d& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

glm::dvec3 randomDirection(std::mt19937& random)
{
    std::normal_distribution<double> normal;
    glm::dvec3 v(normal(random), normal(random), normal(random));
    const double length = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return length > 1e-9 ? v / length : glm::dvec3(1.0, 0.0, 0.0);
}

double uniform(std::mt19937& random, double lo, double hi)
{
    return std::uniform_real_distribution<double>(lo, hi)(random);
}

} // namespace

SoakIk::SoakIk(const ActorDefinitionPtr& humanoid, osg::Group& scene, std::mt19937& random)
    : _random(random), _foreignChain(makeForeignChain()), _goalNodes(new osg::Group)
{
    for (const ChainPlace& place : kPlaces)
        for (IkSolverType solver : {IkSolverType::TwoBone, IkSolverType::Ccd, IkSolverType::Dls})
        {
            if (solver == IkSolverType::TwoBone && !place.twoBone) continue;
            IkChainSpec spec;
            spec.name = std::string(place.name) + "_" + ikSolverName(solver);
            spec.rootJoint = place.root;
            spec.effectorJoint = place.effector;
            spec.effectorOffset = place.offset;
            spec.solver = solver;
            // Few iterations keep 20000 frames of many solves short; one iteration is the hardest case to end well.
            const unsigned iterations[] = {1, 4, 12};
            spec.maxIterations = iterations[_random() % 3];
            spec.tolerance = _random() % 2 ? kDefaultIkTolerance : 1e-2;
            if (place.frozenDof && _random() % 2) spec.dofWeights.push_back({place.frozenDof, 0.0});
            if (!place.twoBone && _random() % 2) spec.jointWeights.push_back({place.root, 0.25});
            _chains.push_back(buildChain(*humanoid, spec));
        }
    scene.addChild(_goalNodes);
    for (unsigned n = 0; n < kMaxGoalNodes / 2; ++n)
        _goalNodes->addChild(new osg::MatrixTransform(randomNodeMatrix()));
}

void SoakIk::equip(ActorNode& actor)
{
    auto ik = std::make_shared<IkController>(_chains[_random() % _chains.size()]);
    ik->setName("ik");
    actor.addController(ik);
    auto follow = std::make_shared<IkNodeController>(_chains[_random() % _chains.size()], randomGoalNode());
    follow->setName("ik_node");
    actor.addController(follow);
}

void SoakIk::moveLast(ActorNode& actor)
{
    for (const char* name : {"ik", "ik_node"})
    {
        const ControllerPtr controller = actor.findController(name);
        if (!controller) continue;
        actor.removeController(controller);
        actor.addController(controller);
    }
}

void SoakIk::randomAction(ActorNode& actor, const std::vector<ActorNode*>& actors)
{
    const auto ik = std::dynamic_pointer_cast<IkController>(actor.findController("ik"));
    const auto follow = std::dynamic_pointer_cast<IkNodeController>(actor.findController("ik_node"));
    if (!ik || !follow)
    {
        equip(actor); // a new actor the soak made
        return;
    }
    IkController& either = _random() % 2 ? static_cast<IkController&>(*ik) : *follow;
    switch (_random() % 9)
    {
    case 0:
    case 1:
    case 2: setRandomGoal(actor, *ik); break;
    case 3: refuseInvalidGoal(either); break;
    case 4: switchChain(either); break;
    case 5:
        switch (_random() % 3)
        {
        case 0:
            if (_random() % 4)
                either.setWeight(uniform(_random, 0.0, 1.0));
            else
            {
                const double before = either.getWeight();
                either.setWeight(kNaN);
                EXPECT_EQ(either.getWeight(), before) << "a NaN weight is refused";
            }
            break;
        case 1: either.setEnabled(!either.getEnabled()); break;
        default: either.clearGoal(); break;
        }
        break;
    case 6: // follow another node (or none), with or without a pole, an offset, the orientation
        follow->setGoalNode(randomGoalNode());
        follow->setPoleNode(_random() % 2 ? randomGoalNode() : nullptr);
        follow->setFollowOrientation(_random() % 2);
        follow->setGoalOffset(_random() % 2 ? osg::Matrixd() : randomNodeMatrix());
        break;
    default: goalNodeAction(actors); break;
    }
}

void SoakIk::newGoals(const std::vector<ActorNode*>& actors, unsigned count)
{
    for (unsigned n = 0; n < count && !actors.empty(); ++n)
    {
        ActorNode& actor = *actors[_random() % actors.size()];
        if (const auto ik = std::dynamic_pointer_cast<IkController>(actor.findController("ik")))
            setRandomGoal(actor, *ik);
    }
}

void SoakIk::setRandomGoal(ActorNode& actor, IkController& ik)
{
    const bool world = _random() % 2;
    // Around the chain's root joint, in the goal's space; the origin for a chain that does not fit the actor.
    osg::Vec3d base;
    double reach = 1.0;
    const IkChainPtr& chain = ik.getChain();
    if (chain && chain->fits(*actor.getDefinition()))
    {
        const unsigned root = chain->getRootJoint();
        base = world ? actor.getJointWorldPosition(root) : actor.getJointModelMatrix(root).getTrans();
        if (!isFinite(base)) base = osg::Vec3d();
        reach = chain->getLength();
    }
    IkGoal goal;
    const glm::dvec3 centre = toGlm(base);
    switch (_random() % 4)
    {
    case 0:
    case 1: goal.position = centre + randomDirection(_random) * (reach * uniform(_random, 0.05, 0.95)); break;
    case 2: goal.position = centre + randomDirection(_random) * (reach * uniform(_random, 1.5, 50.0)); break;
    default:
        goal.position = randomDirection(_random) * (_random() % 2 ? 1e300 : 1.7e308);
        ++_counts.hugeGoals;
        break;
    }
    if (_random() % 3 == 0)
    {
        goal.hasPole = true;
        goal.pole = centre + randomDirection(_random) * (_random() % 8 ? reach : 1e300);
    }
    if (_random() % 3 == 0)
    {
        goal.hasOrientation = true;
        const double scales[] = {1.0, 1e-6, 1e6};
        const glm::dvec3 axis = randomDirection(_random);
        const double angle = uniform(_random, -4.0, 4.0);
        goal.orientation = glm::dquat(std::cos(angle / 2), axis * std::sin(angle / 2)) * scales[_random() % 3];
    }
    EXPECT_TRUE(ik.setGoal(goal, world ? IkGoalSpace::World : IkGoalSpace::Model));
    ++_counts.goalsSet;
}

void SoakIk::refuseInvalidGoal(IkController& ik)
{
    const bool had = ik.hasGoal();
    const IkGoal before = ik.getGoal();
    const IkGoalSpace spaceBefore = ik.getGoalSpace();
    IkGoal goal;
    goal.position = randomDirection(_random);
    const unsigned axis = _random() % 3;
    const double bad = _random() % 2 ? kNaN : (_random() % 2 ? kInf : -kInf);
    switch (_random() % 4)
    {
    case 0: goal.position[axis] = bad; break;
    case 1:
        goal.hasPole = true;
        goal.pole[axis] = bad;
        break;
    case 2:
        goal.hasOrientation = true;
        goal.orientation = glm::dquat(0.0, 0.0, 0.0, 0.0);
        break;
    default:
        goal.hasOrientation = true;
        goal.orientation = glm::dquat(1.0, 0.0, 0.0, 0.0);
        goal.orientation[axis] = _random() % 2 ? bad : 1e200; // the norm overflows
        break;
    }
    EXPECT_FALSE(ik.setGoal(goal, _random() % 2 ? IkGoalSpace::World : IkGoalSpace::Model));
    EXPECT_EQ(ik.hasGoal(), had);
    EXPECT_EQ(ik.getGoalSpace(), spaceBefore);
    EXPECT_TRUE(ik.getGoal().position == before.position && ik.getGoal().pole == before.pole &&
                ik.getGoal().orientation == before.orientation);
    ++_counts.goalsRefused;
}

void SoakIk::switchChain(IkController& ik)
{
    switch (_random() % 6)
    {
    case 0: ik.setChain(_foreignChain); break;
    case 1: ik.setChain(nullptr); break;
    default: ik.setChain(_chains[_random() % _chains.size()]); break;
    }
    ++_counts.chainSwitches;
}

void SoakIk::goalNodeAction(const std::vector<ActorNode*>& actors)
{
    const unsigned numNodes = _goalNodes->getNumChildren();
    switch (_random() % 5)
    {
    case 0:
    case 1: // move one, sometimes to a NaN, infinite, singular or far matrix
        if (numNodes > 0)
            static_cast<osg::MatrixTransform*>(_goalNodes->getChild(_random() % numNodes))
                ->setMatrix(randomNodeMatrix());
        break;
    case 2: // a new node, or one from outside the scene back into it
        if (numNodes >= kMaxGoalNodes) break;
        if (!_detached.empty() && _random() % 2)
        {
            _goalNodes->addChild(_detached.back());
            _detached.pop_back();
        }
        else
            _goalNodes->addChild(new osg::MatrixTransform(randomNodeMatrix()));
        break;
    case 3: // out of the scene, still alive: followed alone (its own matrix is its world matrix)
        if (numNodes == 0 || _detached.size() >= kMaxDetached) break;
        _detached.emplace_back(static_cast<osg::MatrixTransform*>(_goalNodes->getChild(_random() % numNodes)));
        _goalNodes->removeChild(_detached.back());
        break;
    default: // deleted: whoever follows it must stop
    {
        if (numNodes == 0) break;
        const unsigned index = _random() % numNodes;
        osg::observer_ptr<osg::Node> gone = _goalNodes->getChild(index);
        for (ActorNode* actor : actors)
            if (auto follow = std::dynamic_pointer_cast<IkNodeController>(actor->findController("ik_node")))
                if (follow->getGoalNode() == gone.get()) _orphans.push_back(follow);
        _goalNodes->removeChild(index);
        EXPECT_FALSE(gone.valid()) << "the goal node outlived the scene's last reference";
        if (!_orphans.empty()) ++_counts.goalNodesDeleted;
        break;
    }
    }
}

osg::Node* SoakIk::randomGoalNode()
{
    const unsigned numNodes = _goalNodes->getNumChildren();
    if (numNodes == 0 || _random() % 8 == 0)
        return !_detached.empty() && _random() % 2 ? _detached[_random() % _detached.size()].get() : nullptr;
    return _goalNodes->getChild(_random() % numNodes);
}

osg::Matrixd SoakIk::randomNodeMatrix()
{
    switch (_random() % 12)
    {
    case 0: return osg::Matrixd::translate(kNaN, 0.0, 1.0);
    case 1: return osg::Matrixd::translate(0.0, _random() % 2 ? kInf : -kInf, 1.0);
    case 2: return osg::Matrixd::scale(0.0, 0.0, 0.0) * osg::Matrixd::translate(1.0, 0.0, 1.0); // singular
    case 3: return osg::Matrixd::translate(1e300, -1e300, 1e300);
    default:
    {
        const glm::dvec3 axis = randomDirection(_random);
        return osg::Matrixd::rotate(uniform(_random, -3.0, 3.0), toOsg(axis)) *
               osg::Matrixd::translate(uniform(_random, -12.0, 12.0), uniform(_random, -12.0, 12.0),
                                       uniform(_random, 0.0, 2.5));
    }
    }
}

void SoakIk::checkAfterFrame(const std::vector<ActorNode*>& actors, unsigned frame)
{
    for (ActorNode* actor : actors)
        for (const ControllerPtr& controller : actor->getControllers())
        {
            const auto ik = std::dynamic_pointer_cast<IkController>(controller);
            if (!ik) continue;
            // A refused goal is never kept; a solve never reports a NaN error (a sign of NaN in its working).
            if (ik->hasGoal())
            {
                ASSERT_TRUE(ik->getGoal().isValid()) << "frame " << frame;
            }
            const IkResult& result = ik->getLastResult();
            ASSERT_FALSE(std::isnan(result.positionError) || std::isnan(result.orientationError))
                << "frame " << frame << " chain " << (ik->getChain() ? ik->getChain()->getName() : "none");
            if (ik->hasGoal() && ik->getEnabled() && result.reached) ++_counts.solvesReached;
            // A controller that followed a node deleted before this frame, and ran in it, has stopped.
            const bool orphan = std::any_of(_orphans.begin(), _orphans.end(), [&](const auto& o) {
                return o.lock() == controller;
            });
            if (orphan && ik->getEnabled() && ik->getWeight() > 0.0)
            {
                EXPECT_EQ(static_cast<IkNodeController&>(*ik).getGoalNode(), nullptr) << "frame " << frame;
                EXPECT_FALSE(ik->hasGoal()) << "frame " << frame << ": still solving for a deleted node";
                ++_counts.orphansStopped;
            }
        }
    _orphans.clear();
}

} // namespace test
} // namespace osgActor
