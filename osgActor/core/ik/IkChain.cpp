#include <osgActor/core/ik/IkChain>

#include <glm/ext/vector_double3.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace osgActor {

namespace {

const char* const kSolverNames[] = {"twobone", "ccd", "dls"};

std::string quoted(const std::string& name) { return "'" + name + "'"; }

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/** Joints from root down to effector, or empty if the effector is not strictly below the root. */
std::vector<unsigned> pathBetween(const ActorDefinition& definition, unsigned root, unsigned effector)
{
    std::vector<unsigned> path;
    int joint = static_cast<int>(effector);
    while (joint >= 0 && static_cast<unsigned>(joint) != root)
    {
        path.push_back(static_cast<unsigned>(joint));
        joint = definition.getParent(static_cast<unsigned>(joint));
    }
    if (joint < 0 || path.empty()) return {};
    path.push_back(root);
    std::reverse(path.begin(), path.end());
    return path;
}

/** Says what is wrong with one weight, or returns an empty string. */
std::string checkWeight(const IkWeightSpec& weight, const char* kind)
{
    if (std::isfinite(weight.weight) && weight.weight >= 0.0) return std::string();
    std::ostringstream what;
    what << kind << " weight of " << quoted(weight.name) << " is " << weight.weight
         << "; weights must be finite and >= 0";
    return what.str();
}

} // namespace

const char* ikSolverName(IkSolverType solver) { return kSolverNames[static_cast<unsigned>(solver)]; }

bool parseIkSolver(const std::string& text, IkSolverType& solver)
{
    std::string key = text;
    std::transform(key.begin(), key.end(), key.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (unsigned i = 0; i < 3; ++i)
    {
        if (key == kSolverNames[i])
        {
            solver = static_cast<IkSolverType>(i);
            return true;
        }
    }
    return false;
}

bool IkChain::fits(const ActorDefinition& definition) const
{
    if (!fitsLayout(definition.getNumJoints(), definition.getNumDofs())) return false;
    return definition.getJointName(getRootJoint()) == _spec.rootJoint &&
           definition.getJointName(getEffectorJoint()) == _spec.effectorJoint;
}

IkChainBuildResult buildIkChain(const ActorDefinition& definition, const IkChainSpec& spec)
{
    IkChainBuildResult result;
    auto refuse = [&](const std::string& why) {
        result.error = "IK chain " + quoted(spec.name) + " of actor " + quoted(definition.getName()) + ": " + why;
        return result;
    };
    if (spec.name.empty()) return refuse("a chain needs a name");
    const int root = definition.findJoint(spec.rootJoint);
    if (root < 0) return refuse("no root joint named " + quoted(spec.rootJoint));
    const int effector = definition.findJoint(spec.effectorJoint);
    if (effector < 0) return refuse("no effector joint named " + quoted(spec.effectorJoint));
    std::vector<unsigned> joints =
        pathBetween(definition, static_cast<unsigned>(root), static_cast<unsigned>(effector));
    if (joints.empty())
        return refuse("effector " + quoted(spec.effectorJoint) + " is not below root " + quoted(spec.rootJoint) +
                      (root == effector ? " (a chain needs at least one bone)" : ""));
    if (!isFinite(spec.effectorOffset)) return refuse("the effector offset is not finite");
    if (spec.maxIterations == 0) return refuse("a chain needs at least one iteration");
    if (!(spec.tolerance > 0.0 && spec.tolerance < 1.0))
    {
        std::ostringstream what;
        what << "tolerance " << spec.tolerance << " is not in (0, 1)";
        return refuse(what.str());
    }

    // The reach: every bone below the root, then the effector offset. Translation DOFs are not counted.
    double length = glm::length(spec.effectorOffset);
    for (unsigned i = 1; i < joints.size(); ++i) length += glm::length(definition.getOffsetTranslation(joints[i]));
    if (!(length > 0.0)) return refuse("its bones have no length");

    // Weights: joint weight (default 1) times the chain's DOF weight or else the definition's.
    std::vector<double> jointWeights(joints.size(), 1.0);
    for (const IkWeightSpec& w : spec.jointWeights)
    {
        const auto it = std::find_if(joints.begin(), joints.end(),
                                     [&](unsigned j) { return definition.getJointName(j) == w.name; });
        if (it == joints.end()) return refuse("joint weight names " + quoted(w.name) + ", not a joint of the chain");
        const std::string error = checkWeight(w, "joint");
        if (!error.empty()) return refuse(error);
        jointWeights[static_cast<unsigned>(it - joints.begin())] = w.weight;
    }
    std::vector<double> dofWeights(definition.getNumDofs());
    for (unsigned d = 0; d < definition.getNumDofs(); ++d) dofWeights[d] = definition.getDofWeight(d);
    for (const IkWeightSpec& w : spec.dofWeights)
    {
        const int dof = definition.findDof(w.name);
        if (dof < 0 ||
            std::find(joints.begin(), joints.end(), definition.getDofJoint(static_cast<unsigned>(dof))) == joints.end())
            return refuse("DOF weight names " + quoted(w.name) + ", not a DOF of the chain");
        const std::string error = checkWeight(w, "DOF");
        if (!error.empty()) return refuse(error);
        dofWeights[static_cast<unsigned>(dof)] = w.weight;
    }

    std::shared_ptr<IkChain> chain(new IkChain);
    chain->_spec = spec;
    chain->_length = length;
    chain->_numDefinitionJoints = definition.getNumJoints();
    chain->_numDefinitionDofs = definition.getNumDofs();
    double largestWeight = 0.0;
    for (unsigned c = 0; c < joints.size(); ++c)
    {
        const unsigned joint = joints[c];
        chain->_firstJointDofs.push_back(static_cast<unsigned>(chain->_dofs.size()));
        const JointKinematics& kinematics = definition.getKinematics(joint);
        const unsigned first = definition.getFirstDof(joint);
        for (unsigned d = first; d < first + definition.getNumJointDofs(joint); ++d)
        {
            const double weight = jointWeights[c] * dofWeights[d];
            if (!(weight > 0.0)) continue; // frozen
            IkChainDof chainDof;
            chainDof.dof = d;
            chainDof.chainJoint = c;
            chainDof.type = definition.getDofType(d);
            for (std::uint8_t slot = 0; slot < kinematics.numRotations; ++slot)
                if (kinematics.rotationDof[slot] == d) chainDof.rotationSlot = slot;
            chainDof.translationMode = kinematics.translationMode;
            chainDof.weight = weight;
            chainDof.min = definition.getDofRangeMin(d); // the limits, within +-kMaxDofMagnitude
            chainDof.max = definition.getDofRangeMax(d);
            chain->_dofs.push_back(chainDof);
            largestWeight = std::max(largestWeight, weight);
        }
    }
    chain->_firstJointDofs.push_back(static_cast<unsigned>(chain->_dofs.size()));
    if (chain->_dofs.empty()) return refuse("it has no DOF to drive (none active, or every weight is 0)");
    for (IkChainDof& d : chain->_dofs) d.weight /= largestWeight;
    chain->_joints = std::move(joints);

    // Two-bone layout: root, middle, effector; exactly one driven DOF on the middle joint, a rotation (the bend);
    // a driven rotation on the root to aim with.
    if (chain->getNumJoints() == 3)
    {
        const unsigned middleFirst = chain->_firstJointDofs[1];
        const unsigned middleCount = chain->_firstJointDofs[2] - middleFirst;
        bool rootRotates = false;
        for (unsigned i = 0; i < chain->_firstJointDofs[1]; ++i)
            rootRotates = rootRotates || isRotation(chain->_dofs[i].type);
        if (middleCount == 1 && isRotation(chain->_dofs[middleFirst].type) && rootRotates)
            chain->_twoBoneBendDof = static_cast<int>(middleFirst);
    }
    if (spec.solver == IkSolverType::TwoBone && !chain->isTwoBoneLayout())
        return refuse("the two-bone solver needs three joints (root, middle, effector), exactly one driven DOF on "
                      "the middle joint and that one a rotation (give the others weight 0), and a driven rotation "
                      "on the root; use 'ccd' or 'dls' for other chains");
    result.chain = std::move(chain);
    return result;
}

} // namespace osgActor
